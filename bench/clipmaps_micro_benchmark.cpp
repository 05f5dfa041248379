// Google Benchmark micro-benchmarks of the clipmap update (clipmap_update.hpp), the work a
// worker does for every move: the texels (own height, coarser surface) of the samples the levels
// gain, from the store's subsampled levels or prefiltered by least squares (clipmap_prefilter.hpp).
// Items per second = texels made. The sampler reads an in-memory 4097^2 grid, so the figures are
// the update's own cost without the tile cache. Run:
// build/release/bench/tellus_micro_benchmarks --benchmark_filter=Clipmap
#include <benchmark/benchmark.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "tellus/lod/clipmaps/clipmap_update.hpp"

namespace tellus {
namespace {

constexpr int kSide = 4097;

const std::vector<float>& terrain() {
  static const std::vector<float> heights = [] {
    std::vector<float> h(std::size_t(kSide) * kSide);
    for (int y = 0; y < kSide; ++y) {
      for (int x = 0; x < kSide; ++x) {
        h[std::size_t(y) * kSide + std::size_t(x)] =
            float(800.0 + 400.0 * std::sin(0.013 * x) * std::cos(0.017 * y) + 35.0 * std::sin(0.41 * x + 0.29 * y));
      }
    }
    return h;
  }();
  return heights;
}

float storedSample(int level, glm::ivec2 s) {
  const std::vector<float>& h = terrain();
  const int x = std::clamp(s.x << level, 0, kSide - 1), y = std::clamp(s.y << level, 0, kSide - 1);
  return h[std::size_t(y) * kSide + std::size_t(x)];
}

// args: prefilter (0 or 1), samples the viewer moves a frame (0: a whole fill).
void BM_ClipmapUpdate(benchmark::State& state) {
  const clipmaps::ClipmapShape shape = clipmaps::ClipmapShape::create(255, 7).value();
  const clipmaps::LevelFilter filter{state.range(0) != 0};
  const int step = int(state.range(1));
  glm::dvec2 viewer(2048.0, 2048.0);
  std::vector<glm::ivec2> held = clipmaps::placeLevels(shape, viewer);
  std::uint64_t texels = 0;
  for (auto _ : state) {
    viewer.x += step;
    if (viewer.x > 3000.0) viewer.x = 1000.0;
    const clipmaps::ClipmapUpdate update =
        clipmaps::buildClipmapUpdate(shape, step == 0 ? nullptr : &held, viewer, storedSample, filter);
    held = update.origins;
    texels += update.samples;
    benchmark::DoNotOptimize(update.rects.data());
  }
  state.SetItemsProcessed(std::int64_t(texels));
}
BENCHMARK(BM_ClipmapUpdate)->ArgNames({"prefilter", "step"})->Args({0, 0})->Args({1, 0})->Args({0, 8})->Args({1, 8})->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace tellus
