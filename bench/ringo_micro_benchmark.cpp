// Google Benchmark micro-benchmarks of RINGO's block rebuild (seed 002), the work its
// reorganisation does on worker threads for every block a move or a new depth needs: building
// a block's static mesh (ECEF positions with the geoid, collapsed edge positions, normals) from
// its heights, and with a new depth's morph source its vertices' morph deltas. Items per second
// = vertices built. Run:
// build/release/bench/tellus_micro_benchmarks --benchmark_filter=Ringo
#include <benchmark/benchmark.h>

#include <cmath>
#include <filesystem>
#include <memory>
#include <vector>

#include "tellus/dem/geoid.hpp"
#include "tellus/lod/ringo/ringo_block_mesh.hpp"
#include "tellus/lod/ringo/ringo_morph.hpp"

namespace tellus {
namespace {

const Geoid* egm96() {
  static const Result<Geoid> geoid =
      Geoid::load(std::filesystem::path(TELLUS_SHARED_DATA_DIR) / "egm96-geoid/egm96_15.gtx");
  return geoid ? &geoid.value() : nullptr;
}

// The previous depth's surface around `block`'s tile: its parent and the parent's eight
// neighbours as level-0 blocks (what a new depth's central blocks morph from).
std::shared_ptr<RingoMorphSource> parentSurface(const RingoBlock& block) {
  auto source = std::make_shared<RingoMorphSource>(block.key.depth - 1, 0.5f);
  const GeoTileKey parent{block.key.depth - 1, block.key.x / 2, block.key.y / 2};
  constexpr int kCells = 256;
  for (int dy = -1; dy <= 1; ++dy) {
    for (int dx = -1; dx <= 1; ++dx) {
      auto heights = std::make_shared<std::vector<float>>(std::size_t(kCells + 1) * (kCells + 1));
      for (std::size_t k = 0; k < heights->size(); ++k) {
        (*heights)[k] = float(1400.0 + 700.0 * std::sin(0.031 * double(k)));
      }
      auto deltas = std::make_shared<std::vector<float>>(heights->size(), 12.5f);
      source->add({parent.depth, parent.x + dx, parent.y + dy}, {kCells, heights, deltas});
    }
  }
  return source;
}

// A level-`state.range(0)` block of 256-cell tiles over the Japanese Alps (depth 10), with
// kilometres of relief; the geoid when state.range(1) is 1; morphing from the depth-9 surface
// (itself mid-morph) when state.range(2) is 1.
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
  const std::shared_ptr<RingoMorphSource> morphFrom =
      state.range(2) ? parentSurface(block) : nullptr;
  for (auto _ : state) {
    benchmark::DoNotOptimize(buildRingoBlockMesh(block, cells, heights, geoid, morphFrom.get()));
  }
  state.SetItemsProcessed(std::int64_t(state.iterations()) * std::int64_t(heights.size()));
}
BENCHMARK(BM_RingoBlockMesh)
    ->ArgsProduct({{0, 2}, {0, 1}, {0, 1}})
    ->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace tellus
