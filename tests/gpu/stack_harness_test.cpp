// The quality harness on 3D terrain (path_benchmark.hpp: runDepthTruthPath): stacks-full judged
// against itself scores no crack and no error; the same renderer with holes, or drawn 3 % too
// high, is caught: cracks where the background shows through the holes, screen-space error
// along the view rays where it shows the terrain behind them or sits above the truth.
#include <gtest/gtest.h>

#include <cmath>

#include "support/gl_test.hpp"
#include "tellus/eval/camera_path.hpp"
#include "tellus/eval/path_benchmark.hpp"
#include "tellus/render/stacks/stacks_full_renderer.hpp"
#include "tellus/stacks/stack_generator.hpp"
#include "tellus/stacks/stack_surface.hpp"

namespace tellus {
namespace {

class StackHarnessTest : public test::GlTest {
 protected:
  void SetUp() override {
    test::GlTest::SetUp();
    HeightGrid grid(96, 80);
    for (int y = 0; y < grid.height; ++y) {
      for (int x = 0; x < grid.width; ++x) {
        grid.at(x, y) = float(40.0 * std::sin(x * 0.11) * std::cos(y * 0.09) + 1.2 * x);
      }
    }
    grid.spacingXM = grid.spacingYM = 4.0;
    Result<StackTerrain> generated = generateStacks(grid, StackGeneratorOptions{});
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

}  // namespace
}  // namespace tellus
