// Google Benchmark micro-benchmarks of RINGO's block rebuild (seed 002), the work its
// reorganisation does on worker threads for every block a move or a new depth needs: building
// a block's static mesh (ECEF positions with the geoid, collapsed edge positions, normals) from
// its heights. Items per second = vertices built. Run:
// build/release/bench/tellus_micro_benchmarks --benchmark_filter=Ringo
#include <benchmark/benchmark.h>

#include <cmath>
#include <filesystem>
#include <vector>

#include "tellus/dem/geoid.hpp"
#include "tellus/lod/ringo/ringo_block_mesh.hpp"

namespace tellus {
namespace {

const Geoid* egm96() {
  static const Result<Geoid> geoid =
      Geoid::load(std::filesystem::path(TELLUS_SHARED_DATA_DIR) / "egm96-geoid/egm96_15.gtx");
  return geoid ? &geoid.value() : nullptr;
}

// A level-`state.range(0)` block of 256-cell tiles over the Japanese Alps (depth 10), with
// kilometres of relief; the geoid when state.range(1) is 1.
void BM_RingoBlockMesh(benchmark::State& state) {
  const int level = int(state.range(0));
  const int cells = 256 >> level;
  const RingoBlock block{true, GlobalTiling::tileAt(10, 36.3, 137.6), level};
  std::vector<float> heights(std::size_t(cells + 1) * std::size_t(cells + 1));
  for (int j = 0; j <= cells; ++j) {
    for (int i = 0; i <= cells; ++i) {
      heights[std::size_t(j) * std::size_t(cells + 1) + std::size_t(i)] =
          float(1500.0 + 800.0 * std::sin(0.05 * i) * std::cos(0.07 * j));
    }
  }
  const Geoid* geoid = state.range(1) ? egm96() : nullptr;
  if (state.range(1) && !geoid) {
    state.SkipWithError("no EGM96 grid in the shared data");
    return;
  }
  for (auto _ : state) {
    benchmark::DoNotOptimize(buildRingoBlockMesh(block, cells, heights, geoid));
  }
  state.SetItemsProcessed(std::int64_t(state.iterations()) * std::int64_t(heights.size()));
}
BENCHMARK(BM_RingoBlockMesh)->ArgsProduct({{0, 2}, {0, 1}})->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace tellus
