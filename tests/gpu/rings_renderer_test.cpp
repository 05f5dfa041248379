// The rings renderer on a real store: crack-free along a path while tiles stream into a small
// GPU cache, a patch whose tiles never arrive draws from its ancestor, culling drops only what
// is off screen, and with every patch at full detail it reproduces the reference mesh exactly
// 100 km from the world origin (camera-relative precision). The screen-space error shading mode
// follows the level each patch's data comes from.
#include <gtest/gtest.h>

#include "support/gl_test.hpp"
#include "support/terrain_fixtures.hpp"
#include "support/test_support.hpp"
#include "tellus/dem/terrain_generator.hpp"
#include "tellus/eval/camera_path.hpp"
#include "tellus/eval/frame_metrics.hpp"
#include "tellus/eval/path_benchmark.hpp"
#include "tellus/render/output/offscreen_target.hpp"
#include "tellus/render/rings/rings_renderer.hpp"
#include "tellus/render/output/snapshot.hpp"

namespace tellus {
namespace {

using test::kSentinel;

class RingsRendererTest : public test::GlTest {
 protected:
  // 1025 x 1025 samples, 200 m apart (205 km square), in 64-cell tiles: 16 x 16 patches,
  // 5 pyramid levels, 4 rings.
  static void SetUpTestSuite() {
    test::GlTest::SetUpTestSuite();
    TerrainParams params;
    params.size = 1025;
    params.seed = 11;
    params.spacingM = 200.0;
    params.reliefM = 2400.0;
    // The store's heights are quantised to 1 cm: judge against what it holds.
    test::GeneratedStore built =
        test::buildGeneratedStore(params, test::processFixtureDir("rings-store"), 64);
    ASSERT_TRUE(built.store);
    store_ = new std::shared_ptr<const TileStore>(built.store);
    grid_ = new HeightGrid(std::move(built.level0));
  }
  static void TearDownTestSuite() {
    delete store_;
    delete grid_;
    store_ = nullptr;
    grid_ = nullptr;
  }

  static std::unique_ptr<RingsRenderer> rings(RingsOptions options) {
    return test::createRings(*store_, std::move(options));
  }

  using Frame = test::RenderedFrame;
  static Frame renderFrame(TerrainRenderer& renderer, const Camera& camera, int width = 480,
                           int height = 270, const RenderSettings& settings = {}) {
    return test::renderFrame(renderer, grid_->worldBounds(), camera, width, height, settings);
  }

  static HeightGrid* grid_;
  static std::shared_ptr<const TileStore>* store_;
};
HeightGrid* RingsRendererTest::grid_ = nullptr;
std::shared_ptr<const TileStore>* RingsRendererTest::store_ = nullptr;

// A camera low over the terrain's centre looking north-east and down.
Camera lowCamera(const HeightGrid& grid) {
  Camera camera;
  const Aabb bounds = grid.worldBounds();
  camera.position = {bounds.centre().x, bounds.centre().y, 0.0};
  camera.position.z = grid.heightAtWorld(camera.position.x, camera.position.y) + 1500.0;
  camera.yawDeg = 40.0;
  camera.pitchDeg = -20.0;
  camera.fovYDeg = 60.0;
  return camera;
}

TEST_F(RingsRendererTest, RingsCoverTheTerrainWithFewerTrianglesFarAway) {
  RingsOptions options;
  options.waitForTiles = true;
  std::unique_ptr<RingsRenderer> renderer = rings(options);
  ASSERT_TRUE(renderer);
  EXPECT_EQ(renderer->patchesX(), 16);
  EXPECT_EQ(renderer->rings().rings(), 4);  // reach 15: the whole terrain from any patch
  Frame frame = renderFrame(*renderer, lowCamera(*grid_));
  const RingsFrameInfo& info = renderer->lastFrame();
  EXPECT_EQ(info.centreX, 8);
  EXPECT_EQ(info.centreY, 8);
  EXPECT_EQ(info.windowPatches, 256);
  EXPECT_LT(info.visiblePatches, 200);  // culled: the camera looks north-east
  EXPECT_GT(info.patchesPerLod[0], 0);
  EXPECT_GT(info.patchesPerLod[3], 0);
  EXPECT_EQ(info.fallbackPatches, 0);  // every tile it needs is resident
  EXPECT_EQ(info.misses, info.uploads);
  EXPECT_GT(test::luminanceStdDev(frame.colour), 10.0);
}

// The screen-space error mode colours each pixel by the geometric error of the level its data
// comes from: with the red threshold near 0 px, exactly the patches drawn from level 0 (no
// error) stay green, as the LOD mode shows them (palette entry 0: r = 4.5 g).
TEST_F(RingsRendererTest, ScreenSpaceErrorShadingFollowsTheLevelOfTheDrawnData) {
  RingsOptions options;
  options.waitForTiles = true;
  std::unique_ptr<RingsRenderer> renderer = rings(options);
  ASSERT_TRUE(renderer);
  RenderSettings lod;
  lod.mode = ShadingMode::LevelOfDetail;
  RenderSettings sse;
  sse.mode = ShadingMode::ScreenSpaceError;
  sse.sseRedPx = 1e-3f;
  const Frame lodFrame = renderFrame(*renderer, lowCamera(*grid_), 480, 270, lod);
  const Frame sseFrame = renderFrame(*renderer, lowCamera(*grid_), 480, 270, sse);
  int terrain = 0, agree = 0, green = 0, red = 0;
  for (int y = 0; y < 270; ++y) {
    for (int x = 0; x < 480; ++x) {
      const std::uint8_t* l = lodFrame.colour.at(x, y);
      const std::uint8_t* e = sseFrame.colour.at(x, y);
      if (l[0] == kSentinel[0] && l[1] == kSentinel[1] && l[2] == kSentinel[2]) continue;
      ++terrain;
      const bool levelZero = l[0] > 3 * l[1];
      const bool isGreen = e[1] > e[0] && e[2] == 0;
      const bool isRed = e[0] > e[1] && e[2] == 0;
      green += isGreen;
      red += isRed;
      agree += levelZero ? isGreen : isRed;
    }
  }
  ASSERT_GT(terrain, 50000);
  EXPECT_GT(green, terrain / 20);  // both kinds of patches are in view
  EXPECT_GT(red, terrain / 20);
  EXPECT_GT(agree, terrain * 99 / 100);

  // With a generous threshold the same view is green: the errors are small on screen.
  sse.sseRedPx = 1e4f;
  const Frame calm = renderFrame(*renderer, lowCamera(*grid_), 480, 270, sse);
  int reddish = 0;
  for (int y = 0; y < 270; ++y) {
    for (int x = 0; x < 480; ++x) reddish += calm.colour.at(x, y)[0] > calm.colour.at(x, y)[1];
  }
  EXPECT_LT(reddish, 480 * 270 / 100 + (480 * 270 - terrain));  // only the sentinel sky
}

// Streaming through a cache of 10 slots with 2 uploads per frame: patches draw from coarser
// ancestors most of the time, the centre moves across patches, and yet no frame has a crack.
TEST_F(RingsRendererTest, NoCracksAlongAFlyoverWhileTilesStreamIntoASmallCache) {
  Result<CameraPath> path = makeCameraPath("flyover", *grid_);
  ASSERT_TRUE(path);
  const std::vector<Camera> cameras = path->sample(16);
  PathRunOptions options = test::qualityRun(480, 270, 0);
  const CoverageMasks coverage = test::referenceCoverage(*grid_, cameras, options);

  for (const bool stream : {true, false}) {
    RingsOptions ringsOptions;
    ringsOptions.gpuSlots = stream ? 10 : 200;
    ringsOptions.maxUploadsPerFrame = 2;
    ringsOptions.waitForTiles = !stream;
    std::unique_ptr<RingsRenderer> renderer = rings(ringsOptions);
    ASSERT_TRUE(renderer);
    const int startX = renderer->rings().centreX(), startY = renderer->rings().centreY();
    Result<PathRun> run = runPath(*renderer, cameras, *grid_, options, coverage);
    ASSERT_TRUE(run) << run.error().message;
    std::uint64_t misses = 0;
    for (const FrameRecord& f : run->frames) {
      EXPECT_EQ(f.crackPixels, 0u) << "frame " << f.index << (stream ? " streaming" : "");
      misses += f.stats.cacheMisses;
    }
    EXPECT_GT(misses, 0u);
    EXPECT_TRUE(renderer->rings().centreX() != startX || renderer->rings().centreY() != startY);
    if (stream) {
      EXPECT_GT(renderer->residency().evictions(), 0u);
    } else {
      // With every tile resident the error is that of the rings' levels of detail alone.
      EXPECT_LT(run->errors.percentile(0.95), 2.0);
    }
  }
}

// The popping metric on rings: a still camera redraws the same selection (0 px, exactly); along
// the flyover the centre patch moves, the rings' levels shift under the surface, and it shows.
TEST_F(RingsRendererTest, PoppingIsZeroForAStillCameraAndShowsWhenTheRingsMove) {
  Result<CameraPath> path = makeCameraPath("flyover", *grid_);
  ASSERT_TRUE(path);
  RingsOptions ringsOptions;
  ringsOptions.waitForTiles = true;
  const PathRunOptions options = test::qualityRun(320, 180, 1);

  const std::vector<Camera> still(3, path->sample(16)[5]);
  std::unique_ptr<RingsRenderer> renderer = rings(ringsOptions);
  ASSERT_TRUE(renderer);
  Result<PathRun> run = runPath(*renderer, still, *grid_, options);
  ASSERT_TRUE(run) << run.error().message;
  for (const FrameRecord& f : run->frames) {
    EXPECT_GT(f.popPixels, 1000u) << "frame " << f.index;
    EXPECT_EQ(f.popPxMax, 0.0) << "frame " << f.index;
  }

  renderer = rings(ringsOptions);
  ASSERT_TRUE(renderer);
  run = runPath(*renderer, path->sample(16), *grid_, options);
  ASSERT_TRUE(run) << run.error().message;
  int popped = 0;
  for (const FrameRecord& f : run->frames) popped += f.popPxMax > 0.5 ? 1 : 0;
  EXPECT_GT(popped, 0);
  EXPECT_GT(run->popping.max, 0.5);
}

// The level-0 and level-1 tiles under the camera never arrive: those patches draw from the
// level-2 ancestor — a coarser surface, but no hole and no crack.
TEST_F(RingsRendererTest, APatchWhoseTilesAreMissingDrawsFromItsAncestor) {
  const Camera camera = lowCamera(*grid_);
  RingsOptions full;
  full.waitForTiles = true;
  std::unique_ptr<RingsRenderer> complete = rings(full);
  ASSERT_TRUE(complete);
  const Frame reference = renderFrame(*complete, camera);

  RingsOptions withheld = full;
  withheld.tileFilter = [](TileKey key) {
    return !(key.level <= 1 && (key.x << key.level) <= 9 && ((key.x + 1) << key.level) > 8 &&
             (key.y << key.level) <= 9 && ((key.y + 1) << key.level) > 8);
  };
  std::unique_ptr<RingsRenderer> renderer = rings(withheld);
  ASSERT_TRUE(renderer);
  const Frame frame = renderFrame(*renderer, camera);
  EXPECT_GT(renderer->lastFrame().fallbackPatches, 0);
  EXPECT_EQ(renderer->residency().slotOf({0, 8, 8}), -1);
  EXPECT_EQ(renderer->residency().slotOf({1, 4, 4}), -1);
  EXPECT_GE(renderer->residency().slotOf({2, 2, 2}), 0);

  const CrackReport cracks =
      detectCracks(frame.colour, kSentinel, coverageFromDepth(reference.depth));
  EXPECT_EQ(cracks.crackPixels, 0u);
  // The surface differs (it is the ancestor's) where the missing tiles are.
  std::size_t differing = 0;
  for (std::size_t i = 0; i < frame.colour.pixels.size(); ++i) {
    differing += frame.colour.pixels[i] != reference.colour.pixels[i] ? 1 : 0;
  }
  EXPECT_GT(differing, frame.colour.pixels.size() / 100);
}

// Frustum culling is conservative: the same image with and without it, from fewer patches.
TEST_F(RingsRendererTest, CullingDropsOnlyWhatIsOffScreen) {
  RingsOptions culled;
  culled.waitForTiles = true;
  culled.gpuSlots = 400;
  RingsOptions all = culled;
  all.frustumCulling = false;
  std::unique_ptr<RingsRenderer> a = rings(culled), b = rings(all);
  ASSERT_TRUE(a && b);
  // Oblique views in several directions from high up and from 30 m above the ground, below
  // the highest point of the patch underneath (whose box must keep its full height range).
  for (const double above : {1500.0, 30.0}) {
    for (const double yaw : {40.0, 160.0, 280.0}) {
      Camera camera = lowCamera(*grid_);
      camera.position.z += above - 1500.0;
      camera.pitchDeg = above > 100.0 ? -20.0 : -45.0;
      camera.fovYDeg = above > 100.0 ? 60.0 : 30.0;
      camera.yawDeg = yaw;
      if (above < 100.0) {
        ASSERT_GT(store_->get()->find({0, 8, 8})->stats.maxHeightM, camera.position.z);
      }
      const Frame withCulling = renderFrame(*a, camera);
      const Frame without = renderFrame(*b, camera);
      EXPECT_LT(a->lastFrame().visiblePatches, b->lastFrame().visiblePatches / 2);
      EXPECT_EQ(b->lastFrame().visiblePatches, 256);
      EXPECT_TRUE(withCulling.colour.pixels == without.colour.pixels)
          << above << " m above the ground, yaw " << yaw;
    }
  }
}

// Every patch at full detail draws exactly the reference mesh, up close, 100 km from the world
// origin: a walk 2 m above the ground scores a negligible screen-space error.
TEST_F(RingsRendererTest, FullDetailMatchesTheReferenceMeshFarFromTheOrigin) {
  Result<CameraPath> path = makeCameraPath("walk", *grid_);
  ASSERT_TRUE(path);
  const std::vector<Camera> cameras = path->sample(4);
  ASSERT_GT(cameras.front().position.x, 90000.0);
  ASSERT_GT(cameras.front().position.y, 90000.0);
  RingsOptions options;
  options.bruteForce = true;
  options.waitForTiles = true;
  options.gpuSlots = 400;
  std::unique_ptr<RingsRenderer> renderer = rings(options);
  ASSERT_TRUE(renderer);
  PathRunOptions run = test::qualityRun(480, 270, 0);
  Result<PathRun> result = runPath(*renderer, cameras, *grid_, run);
  ASSERT_TRUE(result) << result.error().message;
  EXPECT_LT(result->errors.mean(), 0.05);
  EXPECT_LT(result->errors.percentile(0.95), 0.1);
}

}  // namespace
}  // namespace tellus
