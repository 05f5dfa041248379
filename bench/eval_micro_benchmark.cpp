// Google Benchmark micro-benchmarks of the harness's screen-space error measures: the flat
// world's (frame_metrics.hpp: each drawn point moved vertically onto the height grid) and 3D
// terrain's (depth_truth_error.hpp: onto the tangent planes of a truth depth image). Both run
// once per measured frame, twice with popping (against the truth, and against the previous
// selection's render), so their cost adds to every `tellus bench --quality` frame. The frames:
// 1280 x 720, a plane seen from 150 m up, pitched 12 degrees down as the flyover looks, drawn
// 0.5 m high (every pixel differs, by about a pixel near the bottom). Items per second = pixels.
// Run: build/release/bench/tellus_micro_benchmarks --benchmark_filter=ErrorMeasure
#include <benchmark/benchmark.h>

#include <vector>

#include "tellus/eval/depth_truth_error.hpp"
#include "tellus/eval/frame_metrics.hpp"

namespace tellus {
namespace {

constexpr int kWidth = 1280, kHeight = 720;
constexpr double kPlaneZ = 100.0, kDrawnOffsetM = 0.5;

HeightGrid flatGrid() {
  HeightGrid grid(401, 401);
  grid.spacingXM = grid.spacingYM = 50.0;  // 20 km square
  std::fill(grid.heights.begin(), grid.heights.end(), float(kPlaneZ));
  return grid;
}

ViewSetup flyoverView(const HeightGrid& grid) {
  Camera camera;
  camera.position = {10000.0, 500.0, kPlaneZ + 150.0};
  camera.yawDeg = 0.0;
  camera.pitchDeg = -12.0;
  camera.fovYDeg = 60.0;
  return ViewSetup::create(camera, grid.worldBounds(), kWidth, kHeight);
}

// The depth image a perfect renderer makes of the plane z = planeZ (0 above the horizon).
DepthImage renderPlane(const ViewSetup& view, double planeZ) {
  DepthImage image{view.width, view.height, std::vector<float>(std::size_t(view.width * view.height), 0.0f)};
  for (int y = 0; y < view.height; ++y) {
    for (int x = 0; x < view.width; ++x) {
      const glm::dvec3 a = view.unprojectPixel({x + 0.5, y + 0.5}, 1.0);
      const glm::dvec3 dir = view.unprojectPixel({x + 0.5, y + 0.5}, 0.5) - a;
      if (dir.z >= 0.0) continue;
      const glm::dvec3 hit = a + dir * ((planeZ - a.z) / dir.z);
      glm::dvec2 pixel;
      double depth = 0.0;
      if (!view.projectToPixel(hit, pixel, &depth) || depth <= 0.0) continue;
      image.depth[std::size_t(y * view.width + x)] = float(depth);
    }
  }
  return image;
}

struct Frames {
  HeightGrid grid = flatGrid();
  ViewSetup view = flyoverView(grid);
  DepthImage truth = renderPlane(view, kPlaneZ);
  DepthImage drawn = renderPlane(view, kPlaneZ + kDrawnOffsetM);
};

const Frames& frames() {
  static const Frames made;
  return made;
}

// The flat world's measure of the drawn frame against the height grid.
void BM_ErrorMeasureFlat(benchmark::State& state) {
  const Frames& f = frames();
  for (auto _ : state) {
    const ScreenSpaceError error = measureScreenSpaceError(f.drawn, f.view, f.grid);
    benchmark::DoNotOptimize(error.summary.p99Px);
  }
  state.SetItemsProcessed(std::int64_t(state.iterations()) * kWidth * kHeight);
}
BENCHMARK(BM_ErrorMeasureFlat)->Unit(benchmark::kMillisecond)->UseRealTime();

// 3D terrain's measure: arg 1 against the truth (every pixel differs), 0 against itself (the
// unchanged frame's fast path, as popping between a selection and itself).
void BM_ErrorMeasureDepthTruth(benchmark::State& state) {
  const Frames& f = frames();
  const DepthImage& drawn = state.range(0) != 0 ? f.drawn : f.truth;
  for (auto _ : state) {
    const ScreenSpaceError error = measureDepthTruthError(drawn, f.truth, f.view);
    benchmark::DoNotOptimize(error.summary.p99Px);
  }
  state.SetItemsProcessed(std::int64_t(state.iterations()) * kWidth * kHeight);
}
BENCHMARK(BM_ErrorMeasureDepthTruth)->ArgName("differs")->Arg(1)->Arg(0)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace
}  // namespace tellus
