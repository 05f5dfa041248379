// Google Benchmark micro-benchmarks of the quadrangulation pipeline's CPU reference (seed 003,
// section 3.2): one node of n^3 cells (state.range(0)) through all six stages, on a generated
// terrain with caves, overhangs and an arch, cycling over the nodes that have a surface. Items
// per second = nodes. Run:
// build/release/bench/tellus_micro_benchmarks --benchmark_filter=StackQuad
#include <benchmark/benchmark.h>

#include <cmath>

#include "tellus/formats/stacks/quadrangulation.hpp"
#include "tellus/formats/stacks/stack_generator.hpp"

namespace tellus {
namespace {

const QuantisedStacks& hills() {
  static const QuantisedStacks stacks = [] {
    HeightGrid grid(192, 192);
    for (int y = 0; y < grid.height; ++y) {
      for (int x = 0; x < grid.width; ++x) {
        grid.at(x, y) = float(60.0 * std::sin(x * 0.05) * std::cos(y * 0.04) + 0.6 * x);
      }
    }
    grid.spacingXM = grid.spacingYM = 2.0;
    return QuantisedStacks::from(generateStacks(grid, StackGeneratorOptions{}).value(), 2.0).value();
  }();
  return stacks;
}

void BM_StackQuadNode(benchmark::State& state) {
  QuadParams params;
  params.nodeCells = int(state.range(0));
  const QuantisedStacks& stacks = hills();
  const NodeGrid grid = NodeGrid::of(stacks, params);
  const std::vector<NodeKey> nodes = nodesWithSurface(stacks, params);
  std::size_t next = 0, quads = 0;
  for (auto _ : state) {
    StackMesh mesh;
    quadrangulateNode(stacks, params, grid.origin(nodes[next]), mesh);
    quads += mesh.quadCount();
    benchmark::DoNotOptimize(mesh.indices.data());
    next = (next + 1) % nodes.size();
  }
  state.SetItemsProcessed(std::int64_t(state.iterations()));
  state.counters["quads_per_node"] = double(quads) / double(state.iterations());
}
BENCHMARK(BM_StackQuadNode)->Arg(9)->Arg(17)->Arg(33)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace tellus
