// The quality harness on 3D terrain (path_benchmark.hpp: runDepthTruthPath): stacks-full judged
// against itself scores no crack and no error; the same renderer with holes, or drawn 3 % too
// high, is caught: cracks where the background shows through the holes, screen-space error
// along the view rays where it shows the terrain behind them or sits above the truth.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "support/gl_test.hpp"
#include "support/terrain_fixtures.hpp"
#include "support/stack_fixtures.hpp"
#include "tellus/eval/camera_path.hpp"
#include "tellus/eval/depth_truth_error.hpp"
#include "tellus/eval/frame_metrics.hpp"
#include "tellus/eval/path_benchmark.hpp"
#include "tellus/render/output/offscreen_target.hpp"
#include "tellus/render/stacks/stacks_full_renderer.hpp"
#include "tellus/formats/stacks/stack_generator.hpp"
#include "tellus/formats/stacks/stack_surface.hpp"

namespace tellus {
namespace {

class StackHarnessTest : public test::GlTest {
 protected:
  void SetUp() override {
    test::GlTest::SetUp();
    Result<StackTerrain> generated = test::hillsWithCaves(
        {.amplitudeM = 40.0, .waveX = 0.11, .waveY = 0.09, .riseM = 1.2, .caveScaleM = 0.0});
    ASSERT_TRUE(generated) << generated.error().message;
    stacks_ = std::move(generated.value());
    Result<CameraPath> path = makeCameraPath("flyover", topSurfaceGrid(stacks_));
    ASSERT_TRUE(path) << path.error().message;
    cameras_ = path->sample(4);
    options_.width = 200;
    options_.height = 120;
    options_.warmupFrames = 0;
    options_.quality = true;
  }

  Result<PathRun> run(const StacksRenderOptions& renderOptions, const PathRunOptions& options,
                      const std::vector<DepthImage>* truthDepths, const CoverageMasks& coverage) {
    Result<std::unique_ptr<StacksFullRenderer>> renderer =
        StacksFullRenderer::create(stacks_, renderOptions);
    if (!renderer) return renderer.error();
    return runDepthTruthPath(*renderer.value(), cameras_, stackWorldBounds(stacks_), options,
                             truthDepths, coverage);
  }

  StackTerrain stacks_;
  std::vector<Camera> cameras_;
  PathRunOptions options_;
};

std::uint64_t totalCracks(const PathRun& run) {
  std::uint64_t cracks = 0;
  for (const FrameRecord& f : run.frames) cracks += f.crackPixels;
  return cracks;
}

TEST_F(StackHarnessTest, TheGroundTruthIsExactAndHolesAndOffsetsAreCaught) {
  PathRunOptions truthOptions = options_;
  truthOptions.recordDepths = true;
  Result<PathRun> truth = run({}, truthOptions, nullptr, {});
  ASSERT_TRUE(truth) << truth.error().message;
  ASSERT_EQ(truth->depths.size(), cameras_.size());
  EXPECT_EQ(totalCracks(truth.value()), 0u);
  EXPECT_GT(truth->errors.total, 1000u);
  EXPECT_EQ(truth->errors.max, 0.0);

  // The same renderer judged against the ground truth's depths: still exact.
  Result<PathRun> again = run({}, options_, &truth->depths, truth->coverage);
  ASSERT_TRUE(again);
  EXPECT_EQ(totalCracks(again.value()), 0u);
  EXPECT_EQ(again->errors.max, 0.0);

  // One quad in 25 left out: background through the holes (cracks), the terrain behind them
  // (error along the rays).
  StacksRenderOptions holed;
  holed.holeEvery = 25;
  Result<PathRun> holes = run(holed, options_, &truth->depths, truth->coverage);
  ASSERT_TRUE(holes);
  EXPECT_GT(totalCracks(holes.value()), 0u);
  EXPECT_GT(holes->errors.percentile(0.999), 1.0);

  // Drawn 3 % higher (vertical exaggeration): no crack, an error on most pixels.
  PathRunOptions raisedOptions = options_;
  raisedOptions.settings.verticalExaggeration = 1.03f;
  Result<PathRun> raised = run({}, raisedOptions, &truth->depths, truth->coverage);
  ASSERT_TRUE(raised);
  EXPECT_GT(raised->errors.percentile(0.5), 0.05);
}

// The 3D measure (depth_truth_error.hpp) against a calculation that shares nothing with it:
// drawn with a vertical exaggeration of 1.002, every surface point (x, y, z) of these hills (no
// caves) is drawn at (x, y, 1.002 z), so the flat world's measure of a drawn point P is its
// distance on screen from (P.x, P.y, P.z / 1.002), worked out from the drawn depth alone. The 3D
// measure, from the truth's depth image and its normals, finds the same displacements.
TEST_F(StackHarnessTest, OnRaisedHillsTheErrorIsTheFlatWorldsMeasure) {
  Result<std::unique_ptr<StacksFullRenderer>> renderer = StacksFullRenderer::create(stacks_, {});
  ASSERT_TRUE(renderer) << renderer.error().message;
  const ViewSetup view = ViewSetup::create(cameras_[1], stackWorldBounds(stacks_), 320, 200);
  const test::RenderedFrame truth = test::renderFrame(*renderer.value(), view);
  RenderSettings raised;
  constexpr double kExaggeration = 1.002;
  raised.verticalExaggeration = float(kExaggeration);
  const test::RenderedFrame drawn = test::renderFrame(*renderer.value(), view, raised);
  const ScreenSpaceError error = measureDepthTruthError(drawn.depth, truth.depth, view);
  std::vector<double> expected, difference;
  for (int y = 0; y < view.height; ++y) {
    for (int x = 0; x < view.width; ++x) {
      const float e = error.errorPx[std::size_t(y) * std::size_t(view.width) + std::size_t(x)];
      if (e < 0.0f) continue;
      const glm::dvec2 pixel{x + 0.5, y + 0.5};
      const glm::dvec3 p = view.unprojectPixel(pixel, drawn.depth.at(x, y));
      glm::dvec2 below;
      ASSERT_TRUE(view.projectToPixel({p.x, p.y, p.z / kExaggeration}, below));
      expected.push_back(glm::distance(below, pixel));
      difference.push_back(std::abs(double(e) - expected.back()));
    }
  }
  ASSERT_GT(expected.size(), 10000u);
  const auto quantile = [](std::vector<double> v, double q) {
    std::sort(v.begin(), v.end());
    return v[std::size_t(q * double(v.size() - 1))];
  };
  const double median = quantile(expected, 0.5), p95 = quantile(expected, 0.95);
  std::printf("flat world's measure: median %.3f px, p95 %.3f px; |3D - flat|: median %.4f px, p95 %.4f px, "
              "p99 %.4f px\n",
              median, p95, quantile(difference, 0.5), quantile(difference, 0.95), quantile(difference, 0.99));
  EXPECT_GT(median, 0.2);  // a displacement the measure must see
  EXPECT_LT(quantile(difference, 0.5), 0.01 * median);
  EXPECT_LT(quantile(difference, 0.95), 0.05 * p95);
  // The rest: faces steeper than 78 degrees, where the 3D measure moves along the normal.
  EXPECT_LT(quantile(difference, 0.99), 0.15 * p95);
}

// The open-air test of the crack metric rests on the surface being closed: every view ray that
// meets the solid leaves it through a back face, so the back faces cover exactly the pixels the
// front faces cover. With holes, the background seen through them lies on rays that entered the
// solid and met a back face: holes stay cracks (but for rays that leave through a second hole).
TEST_F(StackHarnessTest, TheBackFacesOfTheClosedSurfaceCoverEveryTerrainPixel) {
  const ViewSetup view =
      ViewSetup::create(cameras_[1], stackWorldBounds(stacks_), options_.width, options_.height);
  const auto render = [&](std::uint32_t holeEvery, test::RenderedFrame& front,
                          std::vector<std::uint8_t>& backCover) {
    StacksRenderOptions renderOptions;
    renderOptions.holeEvery = holeEvery;
    Result<std::unique_ptr<StacksFullRenderer>> renderer =
        StacksFullRenderer::create(stacks_, renderOptions);
    ASSERT_TRUE(renderer) << renderer.error().message;
    front = test::renderFrame(*renderer.value(), view);
    Result<OffscreenTarget> target = OffscreenTarget::create(view.width, view.height, 1);
    ASSERT_TRUE(target);
    target->begin({test::kSentinel[0], test::kSentinel[1], test::kSentinel[2]});
    ASSERT_TRUE(renderer.value()->drawLastFrameBackFaces(view, {}));
    backCover = coverageFromDepth(target->readDepth());
  };
  test::RenderedFrame closed, holed;
  std::vector<std::uint8_t> closedBack, holedBack;
  render(0, closed, closedBack);
  render(25, holed, holedBack);
  const std::vector<std::uint8_t> truthCover = coverageFromDepth(closed.depth);
  std::size_t terrainPixels = 0, mismatched = 0;
  for (std::size_t i = 0; i < truthCover.size(); ++i) {
    terrainPixels += truthCover[i];
    mismatched += truthCover[i] != closedBack[i] ? 1 : 0;
  }
  ASSERT_GT(terrainPixels, 1000u);
  EXPECT_EQ(mismatched, 0u);

  CrackReport cracks = detectCracks(holed.colour, test::kSentinel, truthCover);
  const std::uint64_t holePixels = cracks.crackPixels;
  EXPECT_GT(holePixels, 20u);
  excludeOpenAirGaps(cracks, holedBack);
  // Except where the ray also leaves through a hole (one quad in 25 is missing on the way out
  // too): such a ray crosses no face at all and cannot be told from open air.
  EXPECT_GE(cracks.crackPixels, holePixels * 85 / 100);
  EXPECT_LT(cracks.crackPixels, holePixels + 1);
}

}  // namespace
}  // namespace tellus
