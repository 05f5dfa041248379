// The globe reference drawing a global store (its cut of the store's finest tiles, with skirts):
// where the cut is all deepest tiles it draws what the reference of one deep region draws, and
// no frame of a descent from orbit to 3 km shows a hole, while the cut changes every frame.
#include <cmath>

#include <gtest/gtest.h>
#include <glm/geometric.hpp>

#include "support/gl_test.hpp"
#include "support/globe_fixtures.hpp"
#include "support/terrain_fixtures.hpp"
#include "tellus/core/geo_camera.hpp"
#include "tellus/render/globe/globe_reference_renderer.hpp"

namespace tellus {
namespace {

using GlobeStoreReferenceTest = test::GlTest;

ViewSetup viewFrom(const GeoCamera& camera, int width, int height) {
  return geoViewSetup(camera, chooseGeoClipRange(camera, 0.0, 2000.0), width, height);
}

TEST_F(GlobeStoreReferenceTest, WhereTheCutIsTheDeepestTilesItDrawsTheDeepRegion) {
  // A tolerance so tight that every tile in view is the store's deepest (depth 10 here).
  Result<GlobeReferenceRenderer> cut =
      GlobeReferenceRenderer::create(test::syntheticEarth(), nullptr, nullptr, 0.001);
  ASSERT_TRUE(cut) << cut.error().message;
  const ViewSetup view = viewFrom({42.0, 12.0, 20000.0, 0.0, -90.0, 30.0}, 160, 120);
  const test::RenderedFrame drawn = test::renderFrame(cut.value(), view);
  EXPECT_NE(cut->frameReport().at(0).find("depths 10..10"), std::string::npos)
      << cut->frameReport().at(0);
  Result<HeightGrid> region = readGlobalRegion(*test::syntheticEarth(), 10, {11.5, 41.6, 12.5, 42.4});
  ASSERT_TRUE(region) << region.error().message;
  Result<GlobeReferenceRenderer> whole = GlobeReferenceRenderer::create(region.value(), nullptr);
  ASSERT_TRUE(whole) << whole.error().message;
  const test::RenderedFrame truth = test::renderFrame(whole.value(), view);
  const test::DepthComparison compared = test::compareDepths(drawn, truth, view, 1);
  EXPECT_EQ(compared.holes, 0);
  EXPECT_GT(compared.compared, 15000);
  EXPECT_LT(compared.worstM, 0.5);  // the same triangles: depth-buffer resolution 20 km away
  const double worstM = compared.worstM;
  RecordProperty("worst_m", std::to_string(worstM));
}

// Tiles of different depths meet with T-junctions; the skirts close them (without skirts this
// descent shows 14 holes in frame 3 and 2 in frame 8 at this size).
TEST_F(GlobeStoreReferenceTest, ADescentFromOrbitShowsNoHoleInAnyFrame) {
  Result<GlobeReferenceRenderer> reference = GlobeReferenceRenderer::create(
      test::syntheticEarth(), nullptr, nullptr, GlobeReferenceRenderer::kDefaultStoreTolerancePx);
  ASSERT_TRUE(reference) << reference.error().message;
  int shallowest = 99, deepest = 0;
  for (int frame = 0; frame < 10; ++frame) {
    // 20,000 km to 3 km, geometrically, pitching from straight down to the horizon's side.
    const double t = frame / 9.0;
    const double altitude = 20'000'000.0 * std::pow(3000.0 / 20'000'000.0, t);
    const GeoCamera camera{41.5, 11.5, altitude, 30.0, -90.0 + 78.0 * t, 60.0};
    const ViewSetup view = viewFrom(camera, 640, 360);
    const test::RenderedFrame drawn = test::renderFrame(reference.value(), view);
    EXPECT_EQ(test::groundHoles(drawn, view, altitude > 1e6 ? 1e9 : 60'000.0), 0)
        << "frame " << frame << ": " << reference->frameReport().at(0);
    const std::string report = reference->frameReport().at(0);
    const std::size_t at = report.find("depths ");
    ASSERT_NE(at, std::string::npos) << report;
    int low = 0, high = 0;
    ASSERT_EQ(std::sscanf(report.c_str() + at, "depths %d..%d", &low, &high), 2) << report;
    shallowest = std::min(shallowest, low);
    deepest = std::max(deepest, high);
  }
  EXPECT_LE(shallowest, 2) << "from orbit, the shallow tiles";
  EXPECT_EQ(deepest, 10) << "near the ground, the store's deepest";
}

}  // namespace
}  // namespace tellus
