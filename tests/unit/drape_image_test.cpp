// Drapes for the globe: the Blue Marble colour map with its world file, and refusals.
#include <gtest/gtest.h>

#include "support/test_support.hpp"
#include "tellus/dem/drape_image.hpp"
#include "tellus/dem/geotiff_writer.hpp"

namespace tellus {
namespace {

TEST(DrapeImage, LoadsTheBlueMarble) {
  TELLUS_REQUIRE_SHARED_DATA(data);
  Result<DrapeImage> drape = loadDrapeImage(data / "bluemarble8k-global/BlueMarbleAlbedo.jpg");
  ASSERT_TRUE(drape) << drape.error().message;
  EXPECT_EQ(drape->image.width, 8192);
  EXPECT_EQ(drape->image.height, 4096);
  EXPECT_NEAR(drape->westDeg, -180.0, 1e-6);
  EXPECT_NEAR(drape->eastDeg, 180.0, 1e-6);
  EXPECT_NEAR(drape->northDeg, 90.0, 1e-6);
  EXPECT_NEAR(drape->southDeg, -90.0, 1e-6);
  // The Sahara (23 N, 10 E) is sand, the mid Pacific (0 N, 160 W) deep blue.
  const auto at = [&](double lat, double lon) {
    const int x = int((lon + 180.0) / 360.0 * 8192), y = int((90.0 - lat) / 180.0 * 4096);
    return drape->image.at(x, y);
  };
  EXPECT_GT(at(23.0, 10.0)[0], at(23.0, 10.0)[2] + 40);
  EXPECT_GT(at(0.0, -160.0)[2], at(0.0, -160.0)[0] + 10);  // dark navy: (2, 5, 22)
}

TEST(DrapeImage, RefusesWhatIsNotALatLonColourMap) {
  TELLUS_REQUIRE_SHARED_DATA(data);
  Result<DrapeImage> grey = loadDrapeImage(data / "bluemarble8k-global/BlueMarbleAltitude.jpg");
  ASSERT_FALSE(grey);
  EXPECT_NE(grey.error().message.find("red, green and blue"), std::string::npos);
  Result<DrapeImage> tooBig =
      loadDrapeImage(data / "bluemarble8k-global/BlueMarbleAlbedo.jpg", 4096);
  ASSERT_FALSE(tooBig);
  EXPECT_NE(tooBig.error().message.find("at most 4096"), std::string::npos);
  EXPECT_FALSE(loadDrapeImage(data / "missing.jpg"));
  // A heights GeoTIFF is one band.
  const std::filesystem::path tif = test::freshTestDir() / "one-band.tif";
  HeightGrid grid(4, 4);
  ASSERT_TRUE(writeGeoTiff(grid, tif));
  EXPECT_FALSE(loadDrapeImage(tif));
}

}  // namespace
}  // namespace tellus
