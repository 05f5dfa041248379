// Golden images: renders compared with PNGs committed in tests/golden/ within a tolerance
// (different Mesa/LLVM versions round differently). After an intended change of the
// renderer's output, regenerate them with `make golden-update` (scripts/update-golden.sh),
// look at the new PNGs, and commit them.
#include <cstdlib>

#include <gtest/gtest.h>

#include "support/gl_test.hpp"
#include "support/test_support.hpp"
#include "tellus/dem/dem_loader.hpp"
#include "tellus/dem/terrain_generator.hpp"
#include "tellus/render/output/named_views.hpp"
#include "tellus/render/output/snapshot.hpp"

namespace tellus {
namespace {
namespace fs = std::filesystem;

using GoldenImageTest = test::GlTest;

// Fails if more than 0.5% of the channel values differ by more than 24, or the mean absolute
// difference exceeds 1.5 (of 255).
void compareWithGolden(const RgbImage& actual, const std::string& name) {
  const fs::path golden = fs::path(TELLUS_GOLDEN_DIR) / name;
  const char* update = std::getenv("TELLUS_UPDATE_GOLDEN");
  if (update && std::string(update) == "1") {
    ASSERT_TRUE(writePng(actual, golden));
    GTEST_SKIP() << "updated " << golden;
  }
  Result<RgbImage> expected = readPng(golden);
  ASSERT_TRUE(expected) << expected.error().message << " (run make golden-update)";
  ASSERT_EQ(expected->width, actual.width);
  ASSERT_EQ(expected->height, actual.height);
  size_t bad = 0;
  double sum = 0.0;
  RgbImage diff(actual.width, actual.height);
  for (size_t i = 0; i < actual.pixels.size(); ++i) {
    const int d = std::abs(int(actual.pixels[i]) - int(expected->pixels[i]));
    sum += d;
    bad += d > 24;
    diff.pixels[i] = std::uint8_t(std::min(255, d * 8));
  }
  const double mean = sum / double(actual.pixels.size());
  const bool same = bad <= actual.pixels.size() / 200 && mean <= 1.5;
  if (!same) {
    ASSERT_TRUE(writePng(actual, test::testOutputDir() / ("actual-" + name)));
    ASSERT_TRUE(writePng(diff, test::testOutputDir() / ("diff-" + name)));
  }
  EXPECT_TRUE(same) << name << ": " << bad
                    << " channel values off by more than 24, mean difference " << mean
                    << "; actual and diff images are in " << test::testOutputDir();
}

RgbImage renderView(const HeightGrid& grid, const std::string& view) {
  Result<ReferenceRenderer> renderer = ReferenceRenderer::create(grid);
  EXPECT_TRUE(renderer) << renderer.error().message;
  SnapshotOptions options;
  options.width = 320;
  options.height = 240;
  Result<RgbImage> image =
      renderSnapshot(*renderer, grid, namedView(view, grid, 320.0 / 240.0).value(), options);
  EXPECT_TRUE(image) << image.error().message;
  return image ? image.value() : RgbImage(320, 240);
}

TEST_F(GoldenImageTest, ProceduralTerrainOblique) {
  TerrainParams params;
  params.size = 257;
  params.seed = 7;
  params.spacingM = 120.0;
  compareWithGolden(renderView(generateTerrain(params), "oblique"), "procedural-oblique.png");
}

TEST_F(GoldenImageTest, SanFranciscoGeoTiffOverview) {
  TELLUS_REQUIRE_SHARED_DATA(data);
  Result<HeightGrid> grid = loadDem({data / "geotiff-float32-sanfrancisco" / "elev.tif"});
  ASSERT_TRUE(grid) << grid.error().message;
  compareWithGolden(renderView(grid.value(), "overview"), "sanfrancisco-overview.png");
}

TEST_F(GoldenImageTest, SrtmTileOverview) {
  TELLUS_REQUIRE_SHARED_DATA(data);
  Result<HeightGrid> grid = loadDem({data / "srtm3-hgt-east-asia" / "N36E137.hgt"});
  ASSERT_TRUE(grid) << grid.error().message;
  compareWithGolden(renderView(grid.value(), "overview"), "srtm-N36E137-overview.png");
}

}  // namespace
}  // namespace tellus
