#include <gtest/gtest.h>

#include "tellus/dem/height_encoding.hpp"

namespace tellus {
namespace {

TEST(HeightEncoding, TerrainRgbMatchesMapboxFormula) {
  EXPECT_DOUBLE_EQ(decodeTerrainRgb(0, 0, 0), -10000.0);
  // 100000 * 0.1 - 10000 = 0: R*65536 + G*256 + B = 100000 = 1*65536 + 134*256 + 160.
  EXPECT_NEAR(decodeTerrainRgb(1, 134, 160), 0.0, 1e-9);
  // 65536 + 146*256 + 145 = 103057 -> 10305.7 - 10000 = 305.7 m.
  EXPECT_NEAR(decodeTerrainRgb(1, 146, 145), 305.7, 1e-9);
  EXPECT_NEAR(decodeTerrainRgb(255, 255, 255), -10000.0 + 16777215 * 0.1, 1e-6);
}

TEST(HeightEncoding, TerrariumMatchesMapzenFormula) {
  EXPECT_DOUBLE_EQ(decodeTerrarium(128, 0, 0), 0.0);
  EXPECT_DOUBLE_EQ(decodeTerrarium(128, 100, 128), 100.5);
  EXPECT_DOUBLE_EQ(decodeTerrarium(127, 255, 0), -1.0);
  EXPECT_DOUBLE_EQ(decodeTerrarium(0, 0, 0), -32768.0);
}

TEST(HeightEncoding, ParsesNames) {
  EXPECT_EQ(parseHeightEncoding("terrain-rgb"), HeightEncoding::TerrainRgb);
  EXPECT_EQ(parseHeightEncoding("terrarium"), HeightEncoding::Terrarium);
  EXPECT_EQ(parseHeightEncoding("plain"), HeightEncoding::Plain);
  EXPECT_FALSE(parseHeightEncoding("rgb"));
  EXPECT_EQ(heightEncodingName(HeightEncoding::TerrainRgb), "terrain-rgb");
}

}  // namespace
}  // namespace tellus
