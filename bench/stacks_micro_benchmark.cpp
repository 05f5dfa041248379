// Google Benchmark micro-benchmarks of the stack renderers (seed 003). StackQuadNode: the
// quadrangulation pipeline's CPU reference (section 3.2), one node of n^3 cells
// (state.range(0)) through all six stages, on a generated terrain with caves, overhangs and an
// arch, cycling over the nodes that have a surface; items per second = nodes.
// NodeMeshCacheFrame: the octree renderer's mesh cache bookkeeping in one frame at the preset's
// scale: 25,000 drawn meshes looked up, state.range(0) arriving meshes placed in a full pool
// (evicting); items per second = frames. Run:
// BoxCullSetMarkInside: a selection's boxes against a frustum (the renderer's culling pass);
// items per second = boxes.
// build/release/bench/tellus_micro_benchmarks --benchmark_filter='StackQuad|NodeMeshCache|BoxCullSet'
#include <benchmark/benchmark.h>

#include <cmath>
#include <cstdint>
#include <random>
#include <vector>

#include "tellus/core/box_cull_set.hpp"
#include "tellus/core/camera.hpp"
#include "tellus/core/frustum.hpp"
#include "tellus/formats/stacks/quadrangulation.hpp"
#include "tellus/lod/stacks/node_mesh_cache.hpp"
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

void BM_NodeMeshCacheFrame(benchmark::State& state) {
  // The default 512 MiB pool holds about 6 M vertices (64 bytes with their morph targets) and
  // 18 M indices; meshes of 50 to 500 vertices, as the preset's nodes have.
  constexpr std::uint32_t kVertices = 6'000'000, kIndices = 18'000'000;
  constexpr std::uint64_t kDrawn = 25'000;
  const auto arrivals = std::uint64_t(state.range(0));
  NodeMeshCache cache(kVertices, kIndices);
  std::mt19937 random(1);
  const auto meshSize = [&] { return 50u + std::uint32_t(random() % 451); };
  std::uint64_t frame = 1, nextNode = 0;
  // Fill the pool: the drawn nodes, then others until nothing fits without evicting.
  while (cache.vertexPool().used() + 500 < kVertices && cache.indexPool().used() + 1500 < kIndices) {
    const std::uint32_t v = meshSize();
    if (!cache.insert({nextNode++, 0}, v, 3 * v, frame)) break;
  }
  std::uint64_t drawnFirst = 0;  // the drawn nodes: a window sliding over the node keys
  for (auto _ : state) {
    ++frame;
    for (std::uint64_t n = drawnFirst; n < drawnFirst + kDrawn; ++n) {
      benchmark::DoNotOptimize(cache.use({n, 0}, frame));
    }
    for (std::uint64_t a = 0; a < arrivals; ++a) {
      const std::uint32_t v = meshSize();
      benchmark::DoNotOptimize(cache.insert({nextNode++, 0}, v, 3 * v, frame));
    }
    drawnFirst += arrivals;
  }
  state.SetItemsProcessed(std::int64_t(state.iterations()));
  state.counters["evictions_per_frame"] = double(cache.evictions()) / double(state.iterations());
}
BENCHMARK(BM_NodeMeshCacheFrame)->Arg(40)->Arg(1024)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace tellus

namespace tellus {
namespace {

// BoxCullSet::markInside over state.range(0) boxes (a stack selection's size) of a 40 km
// terrain, one view; items per second = boxes.
void BM_BoxCullSetMarkInside(benchmark::State& state) {
  std::mt19937 random(3);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::vector<Aabb> boxes;
  for (std::int64_t i = 0; i < state.range(0); ++i) {
    const glm::dvec3 centre(40000.0 * unit(random), 40000.0 * unit(random), 1000.0 * unit(random));
    const double half = 20.0 + 400.0 * unit(random);
    boxes.push_back({centre - glm::dvec3(half), centre + glm::dvec3(half)});
  }
  const BoxCullSet set(boxes);
  Camera camera;
  camera.position = {20000.0, 5000.0, 1500.0};
  camera.pitchDeg = -20.0;
  const ViewSetup view = ViewSetup::create(camera, Aabb{{0.0, 0.0, 0.0}, {40000.0, 40000.0, 1000.0}}, 1920, 1080);
  const Frustum frustum = Frustum::fromMatrix(view.relativeViewProjection());
  std::vector<std::uint8_t> flags;
  for (auto _ : state) {
    flags.assign(set.size(), 0);
    set.markInside(frustum, camera.position, 1.0, 1, flags);
    benchmark::DoNotOptimize(flags.data());
  }
  state.SetItemsProcessed(state.iterations() * state.range(0));
}
BENCHMARK(BM_BoxCullSetMarkInside)->Arg(25000);

}  // namespace
}  // namespace tellus
