// The globe reference end to end: N37E127 on the ellipsoid from the default camera (straight
// down on the tile's centre) and from an explicit geo camera, with the EGM96 geoid.
#include <gtest/gtest.h>

#include "cli/run_tellus.hpp"
#include "support/test_support.hpp"
#include "tellus/core/rgb_image.hpp"

namespace tellus {
namespace {
namespace fs = std::filesystem;

TEST(GlobeCli, RendersASrtmTileOnTheEllipsoid) {
  TELLUS_REQUIRE_SHARED_DATA(data);
  const fs::path dir = test::freshTestDir();
  const std::string input = quoted(data / "srtm3-hgt-east-asia/N37E127.hgt");
  const std::string geoid = quoted(data / "egm96-geoid/egm96_15.gtx");
  for (const char* camera : {"", "--geo-camera 37.2,127.5,6000,30,-25,55"}) {
    SCOPED_TRACE(camera);
    const fs::path png = dir / "globe.png";
    const RunResult result =
        runTellus(fmt::format("render {} -o {} --algo globe-reference --geoid {} --size 320x180 {}",
                              input, quoted(png), geoid, camera));
    ASSERT_EQ(result.exitCode, 0) << result.output;
    EXPECT_NE(result.output.find("geo camera"), std::string::npos) << result.output;
    Result<RgbImage> image = readPng(png);
    ASSERT_TRUE(image.ok());
    EXPECT_EQ(image->width, 320);
    EXPECT_GT(test::luminanceStdDev(*image), 5.0) << "a blank image";
  }
}

}  // namespace
}  // namespace tellus
