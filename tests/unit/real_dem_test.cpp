// Loading the real DEMs of ../shared/data; the expected figures are the ones SOURCE.txt
// records (verified there with numpy and gdalinfo).
#include <gtest/gtest.h>

#include "support/test_support.hpp"
#include "tellus/dem/dem_loader.hpp"

namespace tellus {
namespace {

TEST(RealDem, SrtmTileN37E127) {
  TELLUS_REQUIRE_SHARED_DATA(data);
  Result<HeightGrid> grid = loadDem({data / "srtm3-hgt-east-asia" / "N37E127.hgt"});
  ASSERT_TRUE(grid) << grid.error().message;
  EXPECT_EQ(grid->width, 1201);
  EXPECT_EQ(grid->height, 1201);
  EXPECT_EQ(grid->filledVoidCount, 5u);
  EXPECT_FLOAT_EQ(grid->heightRange().minM, -15.0f);  // no -32768 spikes left
  EXPECT_FLOAT_EQ(grid->heightRange().maxM, 1456.0f);
  EXPECT_NEAR(grid->spacingYM, 92.5, 0.2);  // 3 arc-seconds of latitude
  EXPECT_NEAR(grid->spacingXM, 73.7, 0.2);  // 3 arc-seconds of longitude at 37.5 N
}

TEST(RealDem, KoreaMosaicIs4801Square) {
  TELLUS_REQUIRE_SHARED_DATA(data);
  Result<HeightGrid> grid = loadDem(test::koreaMosaicTiles(data));
  ASSERT_TRUE(grid) << grid.error().message;
  EXPECT_EQ(grid->width, 4801);
  EXPECT_EQ(grid->height, 4801);
  EXPECT_EQ(grid->filledVoidCount, 48u);  // the tiles' voids, shared edges counted once
  EXPECT_FLOAT_EQ(grid->heightRange().minM, -92.0f);
  EXPECT_FLOAT_EQ(grid->heightRange().maxM, 1883.0f);
  EXPECT_NEAR(grid->spacingXM, 75.1, 0.2);  // at 36 N
  EXPECT_NEAR(grid->spacingYM, 92.5, 0.2);
  EXPECT_NEAR(grid->georef.geoTransform[0], 126.0 - 0.5 / 1200.0, 1e-9);
  EXPECT_NEAR(grid->georef.geoTransform[3], 38.0 + 0.5 / 1200.0, 1e-9);
}

TEST(RealDem, SanFranciscoFloat32GeoTiffInWebMercator) {
  TELLUS_REQUIRE_SHARED_DATA(data);
  Result<HeightGrid> grid = loadDem({data / "geotiff-float32-sanfrancisco" / "elev.tif"});
  ASSERT_TRUE(grid) << grid.error().message;
  EXPECT_EQ(grid->width, 512);
  EXPECT_NEAR(grid->heightRange().minM, 0.436, 0.001);
  EXPECT_NEAR(grid->heightRange().maxM, 114.921, 0.001);
  // Pixels are 6.72 x 6.06 Web Mercator metres; on the ground at 37.8 N that is cos(37.8) less.
  EXPECT_NEAR(grid->spacingXM, 6.7218 * std::cos(37.8 * M_PI / 180.0), 0.02);
  EXPECT_NEAR(grid->spacingYM, 6.0590 * std::cos(37.8 * M_PI / 180.0), 0.02);
}

TEST(RealDem, FujiTerrainRgbTile) {
  TELLUS_REQUIRE_SHARED_DATA(data);
  DemLoadOptions options;
  options.encoding = HeightEncoding::TerrainRgb;
  Result<HeightGrid> grid = loadDem({data / "terrain-rgb-fuji" / "fuji.png"}, options);
  ASSERT_TRUE(grid) << grid.error().message;
  EXPECT_EQ(grid->width, 512);
  EXPECT_NEAR(grid->heightRange().minM, 13.7, 0.01);
  EXPECT_NEAR(grid->heightRange().maxM, 3751.0, 0.01);
}

}  // namespace
}  // namespace tellus
