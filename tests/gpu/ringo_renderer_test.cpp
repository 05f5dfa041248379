// The RINGO renderer (seed 002) on a synthetic global store (a coarse planet and a fine area):
// its central blocks draw the store's surface where the globe reference draws it, the ground
// has no cracks from orbit or near the ground, and while the viewer crosses block borders the
// matrix is rebuilt (derived and reloaded blocks) without a crack in any frame.
#include <cmath>
#include <set>

#include <gtest/gtest.h>
#include <glm/geometric.hpp>

#include "support/gl_test.hpp"
#include "support/globe_fixtures.hpp"
#include "support/terrain_fixtures.hpp"
#include "support/test_support.hpp"
#include "tellus/core/geo_camera.hpp"
#include "tellus/core/geodesy.hpp"
#include "tellus/dem/geotiff_writer.hpp"
#include "tellus/render/globe/globe_reference_renderer.hpp"
#include "tellus/eval/path_benchmark.hpp"
#include "tellus/eval/store_surface.hpp"
#include "tellus/render/ringo/ringo_renderer.hpp"
#include "tellus/tiles/global_store_builder.hpp"
#include "tellus/viewer/globe_camera.hpp"

namespace tellus {
namespace {
namespace fs = std::filesystem;

using RingoRendererTest = test::GlTest;

// The seed's layout (4 rings, blocks a fifth of the distance to the horizon: 121 blocks), which
// these tests' figures are for.
RingoOptions seedLayout() {
  RingoOptions options;
  options.rings = 4;
  options.blocksToHorizon = kRingoBlocksToHorizon;
  return options;
}

// A still's renderer (every frame waits for its blocks), or with `streaming` the viewer's and
// the bench's (blocks arrive when they arrive; the previous ones keep drawing).
std::unique_ptr<RingoRenderer> makeRingo(bool streaming = false) {
  RingoOptions options = seedLayout();
  options.uploadKiBPerFrame = 512;
  options.waitForBlocks = !streaming;
  Result<std::unique_ptr<RingoRenderer>> ringo = RingoRenderer::create(test::syntheticEarth(), options);
  EXPECT_TRUE(ringo) << ringo.error().message;
  return ringo ? std::move(ringo.value()) : nullptr;
}

ViewSetup viewFrom(const GeoCamera& camera, int width, int height) {
  return geoViewSetup(camera, chooseGeoClipRange(camera, 0.0, 2000.0), width, height);
}

TEST_F(RingoRendererTest, TheCentralBlocksDrawTheStoresSurface) {
  std::unique_ptr<RingoRenderer> ringo = makeRingo();
  ASSERT_TRUE(ringo);
  // Straight down from 20 km over the fine area: all in the central blocks.
  const GeoCamera camera{42.0, 12.0, 20000.0, 0.0, -90.0, 30.0};
  const ViewSetup view = viewFrom(camera, 160, 120);
  const test::RenderedFrame drawn = test::renderFrame(*ringo, view);
  const int depth = ringo->frameInfo().depth;
  EXPECT_GE(depth, 8);
  // The globe reference of the same store depth over the view.
  Result<HeightGrid> region = readGlobalRegion(*test::syntheticEarth(), depth, {11.5, 41.6, 12.5, 42.4});
  ASSERT_TRUE(region) << region.error().message;
  Result<GlobeReferenceRenderer> reference = GlobeReferenceRenderer::create(region.value(), nullptr);
  ASSERT_TRUE(reference) << reference.error().message;
  const test::RenderedFrame truth = test::renderFrame(reference.value(), view);
  const test::DepthComparison compared = test::compareDepths(drawn, truth, view, 2);
  EXPECT_EQ(compared.holes, 0);
  EXPECT_GT(compared.compared, 4000);
  EXPECT_LT(compared.worstM, 0.5);  // the same triangles: depth-buffer resolution 20 km away
  const double worstM = compared.worstM;
  RecordProperty("worst_m", std::to_string(worstM));
}

TEST_F(RingoRendererTest, NoHolesFromOrbitOrNearTheGround) {
  std::unique_ptr<RingoRenderer> ringo = makeRingo();
  ASSERT_TRUE(ringo);
  // From orbit the matrix is depth 3: 11 blocks of 22.5 degrees hold the whole visible disc.
  const ViewSetup orbit = viewFrom({30.0, 20.0, 20'000'000.0, 0.0, -90.0, 40.0}, 200, 200);
  EXPECT_EQ(test::groundHoles(test::renderFrame(*ringo, orbit), orbit, 1e9), 0);
  EXPECT_EQ(ringo->frameInfo().depth, 3);
  // 3 km over the fine area looking ahead: every ray that meets the ground within 60 km does.
  const ViewSetup low = viewFrom({41.5, 11.5, 3000.0, 30.0, -12.0, 60.0}, 240, 160);
  const test::RenderedFrame frame = test::renderFrame(*ringo, low);
  EXPECT_EQ(test::groundHoles(frame, low, 60'000.0), 0);
  EXPECT_GT(ringo->frameInfo().blocksDrawn, 9);
}

// The default layout (8 rings of blocks a tenth of the horizon distance: 361 blocks) reaches as
// far as the seed's (4 rings of a fifth): no hole from orbit, none within 90 % of the distance
// to the horizon from 2 km and 300 m up, and no more than the seed's layout anywhere in view
// (beyond the horizon of the ground under the viewer the far plane cuts both).
TEST_F(RingoRendererTest, TheDefaultLayoutReachesAsFarAsTheSeeds) {
  const auto make = [](RingoOptions options) {
    options.waitForBlocks = true;
    Result<std::unique_ptr<RingoRenderer>> made = RingoRenderer::create(test::syntheticEarth(), options);
    EXPECT_TRUE(made) << made.error().message;
    return made ? std::move(made.value()) : nullptr;
  };
  std::unique_ptr<RingoRenderer> defaults = make(RingoOptions{}), seed = make(seedLayout());
  ASSERT_TRUE(defaults && seed);
  EXPECT_EQ(defaults->layout().side(), 19);
  const ViewSetup orbit = viewFrom({30.0, 20.0, 20'000'000.0, 0.0, -90.0, 40.0}, 200, 200);
  EXPECT_EQ(test::groundHoles(test::renderFrame(*defaults, orbit), orbit, 1e9), 0);
  for (const double clearance : {2000.0, 300.0}) {
    const double ground = test::syntheticEarthRelief(41.5, 11.5);
    const GeoCamera camera{41.5, 11.5, ground + clearance, 30.0, -3.0, 60.0};
    const ViewSetup low = geoViewSetup(camera, chooseGeoClipRange(camera, ground, 2000.0), 240, 160);
    const test::RenderedFrame drawn = test::renderFrame(*defaults, low);
    const double horizonM = std::sqrt(2.0 * 6'371'000.0 * clearance);
    EXPECT_EQ(test::groundHoles(drawn, low, 0.9 * horizonM), 0) << clearance;
    EXPECT_LE(test::groundHoles(drawn, low, 1e9),
              test::groundHoles(test::renderFrame(*seed, low), low, 1e9))
        << clearance;
  }
}

TEST_F(RingoRendererTest, CrossingBlockBordersRebuildsTheMatrixWithoutCracks) {
  std::unique_ptr<RingoRenderer> ringo = makeRingo();
  ASSERT_TRUE(ringo);
  int depth = -1;
  for (int step = 0; step < 8; ++step) {
    // Northwards 8 km a step at 2 km: block borders (depth 10: 19.5 km) crossed on the way.
    const GeoCamera camera{41.0 + step * 0.072, 12.0, 3500.0, 0.0, -15.0, 60.0};
    const ViewSetup view = viewFrom(camera, 200, 120);
    const test::RenderedFrame frame = test::renderFrame(*ringo, view);
    EXPECT_EQ(test::groundHoles(frame, view, 40'000.0), 0) << "step " << step;
    if (depth < 0) depth = ringo->frameInfo().depth;
    EXPECT_EQ(ringo->frameInfo().depth, depth) << "one depth along the flight";
  }
  const RingoReorganiserStats stats = ringo->frameInfo().reorganiser;
  EXPECT_GE(stats.moves, 3u);     // the first matrix and at least two border crossings
  EXPECT_GT(stats.derived, 0u);   // D blocks behind the viewer
  EXPECT_EQ(stats.failures, 0u);
  EXPECT_EQ(ringo->frameInfo().blocksResident, 121);
}

// Streaming, as the viewer and the bench draw: a descent from 20,000 km to 3 km in 14 frames,
// the matrix changing depth nearly every frame. No frame has a hole: blocks keep drawing until
// their replacements are copied in, the previous depth's matrix until the new one is filled, and
// the coarser-edge masks follow the blocks as drawn.
TEST_F(RingoRendererTest, AStreamingDescentHasNoHoleInAnyFrame) {
  std::unique_ptr<RingoRenderer> ringo = makeRingo(/*streaming=*/true);
  ASSERT_TRUE(ringo);
  std::set<int> depths;
  GeoCamera camera;
  for (int step = 0; step < 14; ++step) {
    const double altitude = 20'000'000.0 * std::pow(3000.0 / 20'000'000.0, step / 13.0);
    camera = {41.5, 11.5, altitude, 20.0, -90.0 + 70.0 * step / 13.0, 60.0};
    const ViewSetup view = viewFrom(camera, 160, 100);
    const test::RenderedFrame frame = test::renderFrame(*ringo, view);
    EXPECT_EQ(test::groundHoles(frame, view, std::max(60'000.0, 10.0 * altitude)), 0) << "step " << step;
    depths.insert(ringo->frameInfo().depth);
  }
  // Then hovering at 3 km until the matrix has caught up (how many frames that takes depends
  // on the workers' speed): still no hole.
  int settledFrames = 0;
  for (int frame = 0; frame < 400 && settledFrames < 3; ++frame) {
    const int before = ringo->frameInfo().depth;
    const ViewSetup view = viewFrom(camera, 160, 100);
    EXPECT_EQ(test::groundHoles(test::renderFrame(*ringo, view), view, 60'000.0), 0) << "hover " << frame;
    depths.insert(ringo->frameInfo().depth);
    const bool settled = ringo->frameInfo().depth == before && !ringo->frameInfo().reorganising &&
                         ringo->frameInfo().blocksResident == 121;
    settledFrames = settled ? settledFrames + 1 : 0;
  }
  EXPECT_EQ(settledFrames, 3);
  EXPECT_EQ(*depths.begin(), 3);              // from orbit
  EXPECT_GE(ringo->frameInfo().depth, 9);     // 3 km up: depth 9 or 10 (hysteresis)
  EXPECT_GE(depths.size(), 3u);
  EXPECT_EQ(ringo->frameInfo().reorganiser.failures, 0u);
}

// The synthetic Earth with rough hills (250 m, 5 km across) in its fine area: every finer depth
// shows more of them, so a change of depth is a visible step unless it morphs.
double roughRelief(double lat, double lon) {
  constexpr double k = 3.14159265358979323846 / 180.0;
  return test::syntheticEarthRelief(lat, lon) +
         250.0 * std::sin(7200.0 * lat * k) * std::sin(6100.0 * lon * k);
}

std::shared_ptr<const GlobalStore> roughEarth() {
  static const std::shared_ptr<const GlobalStore> store = test::buildSyntheticEarth(roughRelief);
  return store;
}

// A descent from 40 km to 2 km over the rough hills in 40 frames changes the matrix's depth
// every dozen frames, slowly enough for the morph's frames. Each new matrix morphs from the
// surface drawn before it: the worst frame's popping p99 drops well below what replacing the
// matrix at once shows, the error stays about the same, and no frame has a crack.
TEST_F(RingoRendererTest, ADepthChangeMorphsInsteadOfStepping) {
  const std::shared_ptr<const GlobalStore> store = roughEarth();
  ASSERT_TRUE(store);
  std::vector<ViewSetup> views;
  for (int step = 0; step < 40; ++step) {
    const double altitude = 40'000.0 * std::pow(2000.0 / 40'000.0, step / 39.0);
    views.push_back(viewFrom({42.0, 12.0, altitude, 20.0, -60.0 + 35.0 * step / 39.0, 60.0}, 200, 120));
  }
  StoreSurface surface(store, nullptr);
  PathTruth truth;
  truth.surface = surface.truth();
  const PathRunOptions run = test::qualityRun(200, 120, 1);
  Result<GlobeReferenceRenderer> reference = GlobeReferenceRenderer::create(
      store, nullptr, nullptr, GlobeReferenceRenderer::kDefaultStoreTolerancePx);
  ASSERT_TRUE(reference) << reference.error().message;
  Result<PathRun> referenceRun = runViews(reference.value(), views, truth, run);
  ASSERT_TRUE(referenceRun) << referenceRun.error().message;
  std::set<int> depths;
  const auto fly = [&](int morphFrames) {
    RingoOptions options = seedLayout();
    options.waitForBlocks = true;  // depth changes on the same frames, however fast the workers
    options.morphFrames = morphFrames;
    Result<std::unique_ptr<RingoRenderer>> ringo = RingoRenderer::create(store, options);
    EXPECT_TRUE(ringo) << ringo.error().message;
    Result<PathRun> result = runViews(*ringo.value(), views, truth, run, referenceRun->coverage,
                                      [&](int) { depths.insert(ringo.value()->frameInfo().depth); });
    EXPECT_TRUE(result) << result.error().message;
    return std::move(result.value());
  };
  const PathRun stepped = fly(0), morphed = fly(8);
  double worstStepped = 0.0, worstMorphed = 0.0, sseStepped = 0.0, sseMorphed = 0.0;
  std::uint64_t cracks = 0;
  for (std::size_t f = 1; f < stepped.frames.size(); ++f) {
    worstStepped = std::max(worstStepped, stepped.frames[f].popPxP99);
    worstMorphed = std::max(worstMorphed, morphed.frames[f].popPxP99);
    sseStepped = std::max(sseStepped, stepped.frames[f].ssePxP99);
    sseMorphed = std::max(sseMorphed, morphed.frames[f].ssePxP99);
    cracks += stepped.frames[f].crackPixels + morphed.frames[f].crackPixels;
  }
  std::printf("ringo over %zu depths: popping p99, worst frame %.3f px stepped, %.3f px morphed; "
              "SSE p99, worst frame %.3f / %.3f px\n",
              depths.size(), worstStepped, worstMorphed, sseStepped, sseMorphed);
  EXPECT_EQ(cracks, 0u);
  EXPECT_GE(depths.size(), 3u);
  ASSERT_GT(worstStepped, 0.5);  // the depth changes do show as steps
  EXPECT_LT(worstMorphed, 0.5 * worstStepped);
  EXPECT_LT(sseMorphed, 1.5 * sseStepped + 0.1);
}

// The seed's collision test: a walk uphill, the camera kept 2 m above the ground RINGO draws
// (as the viewer does), never goes below the store's surface, which is what RINGO draws there.
TEST_F(RingoRendererTest, AWalkIntoAMountainStaysAboveTheGround) {
  std::unique_ptr<RingoRenderer> ringo = makeRingo();
  ASSERT_TRUE(ringo);
  StoreSurface truth(test::syntheticEarth(), nullptr);
  GlobeCameraController controller;
  GeoCamera camera{41.0, 11.0, 0.0, 180.0, 0.0, 60.0};  // southwards: 500 m uphill in 50 km
  const auto drawnGround = [&](double lat, double lon) { return ringo->groundUnderM(lat, lon); };
  camera.altitudeM = truth.ellipsoidalHeightM(camera.latDeg, camera.lonDeg) + 2.0;
  controller.dropToWalkingHeight(camera, [&](double lat, double lon) {
    return truth.ellipsoidalHeightM(lat, lon);
  });
  const double start = camera.altitudeM;
  GlobeInput forward;
  forward.forward = true;
  forward.fast = true;
  for (int step = 0; step < 24; ++step) {
    test::renderFrame(*ringo, viewFrom(camera, 96, 64));  // the matrix follows the walker
    controller.update(camera, forward, 300.0, 64, drawnGround);
    const double drawn = drawnGround(camera.latDeg, camera.lonDeg);
    ASSERT_TRUE(std::isfinite(drawn)) << "step " << step;
    EXPECT_GE(camera.altitudeM, drawn + 2.0 - 1e-6) << "step " << step;
    EXPECT_NEAR(drawn, truth.ellipsoidalHeightM(camera.latDeg, camera.lonDeg), 0.05)
        << "step " << step;
  }
  EXPECT_GT(camera.altitudeM - start, 300.0) << "the walk climbed";
}

}  // namespace
}  // namespace tellus
