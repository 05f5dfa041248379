// tellus stacks quad: the quadrangulation pipeline (seed 003, section 3.2) over a .tstack level,
// on the CPU reference (oneTBB over nodes) and on the GPU pipeline, with per-stage times per
// node, nodes per second, quads per node, the mesh checks and whether both sides agree.
#include <algorithm>
#include <array>
#include <chrono>

#include <fmt/format.h>
#include <nlohmann/json.hpp>
#include <tbb/task_arena.h>

#include "cli_numbers.hpp"
#include "stack_cli.hpp"
#include "tellus/gl/gpu_wait.hpp"
#include "tellus/core/atomic_output.hpp"
#include "tellus/render/stacks/stack_quad_pipeline.hpp"
#include "tellus/formats/stacks/stack_file.hpp"
#include "tellus/formats/stacks/stack_mesh_check.hpp"

namespace tellus::cli {
namespace {

using Clock = std::chrono::steady_clock;
double secondsSince(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

// `count` nodes spread evenly over `nodes` (all when count is 0 or more than there are).
std::vector<NodeKey> sampleNodes(const std::vector<NodeKey>& nodes, std::size_t count) {
  if (count == 0 || count >= nodes.size()) return nodes;
  std::vector<NodeKey> sample;
  for (std::size_t k = 0; k < count; ++k) sample.push_back(nodes[k * nodes.size() / count]);
  return sample;
}

nlohmann::json stagesJson(const QuadStageTimes& t, double perNode) {
  return {{"density", t.density * perNode},       {"smooth", t.smooth * perNode},
          {"classify", t.classify * perNode},     {"allocate", t.allocate * perNode},
          {"attributes", t.attributes * perNode}, {"faces", t.faces * perNode},
          {"total", t.total() * perNode}};
}

std::string stagesLine(const QuadStageTimes& t, double perNode) {
  return fmt::format("density {:.4f}, smooth {:.4f}, classify {:.4f}, allocate {:.4f}, "
                     "attributes {:.4f}, faces {:.4f}; total {:.4f} ms",
                     t.density * perNode, t.smooth * perNode, t.classify * perNode,
                     t.allocate * perNode, t.attributes * perNode, t.faces * perNode,
                     t.total() * perNode);
}

}  // namespace

void addStacksQuadOptions(CLI::App* quad, StacksQuadOptions& o) {
  quad->add_option("input", o.input, "Stack file (.tstack)")->required();
  quad->add_option("--level", o.level, "Pyramid level to quadrangulate (0: finest)")
      ->check(integerIn(0, 30));
  quad->add_option("--node-cells", o.params.nodeCells, "Cells per node side (the seed: 17)")
      ->check(integerIn(3, 64));
  quad->add_option("--filter", o.filter, "Smoothing filter: gauss or box")
      ->check(CLI::IsMember({"gauss", "box"}));
  quad->add_option("--radius", o.params.filterRadius, "Smoothing radius r (2r + 1 taps), 0 to 4")
      ->check(integerIn(0, 4));
  quad->add_option("--cell-m", o.cellM, "Density cell height, metres (default: the stacks' spacing)")
      ->check(numberIn(0.01, 10000.0));
  quad->add_option("--nodes", o.nodes, "Quadrangulate this many nodes spread over the terrain (0: all)")
      ->check(integerIn(0, 1000000000));
  quad->add_option("--batch", o.batch, "GPU nodes per dispatch")->check(integerIn(1, 4096));
  quad->add_flag("--no-gpu", o.noGpu, "Only the CPU reference");
  quad->add_flag("--no-cpu", o.noCpu, "Only the GPU pipeline");
  quad->add_option("--json", o.json, "Write the figures as JSON to this file");
}

int runStacksQuad(StacksQuadOptions o) {
  o.params.filter = o.filter == "box" ? SmoothingFilter::Box : SmoothingFilter::Gauss;
  if (Status ok = o.params.check(); !ok) return fail(ok.error());
  if (o.noCpu && o.noGpu) return fail(makeError("--no-cpu and --no-gpu leave nothing to run"));
  Result<std::vector<StackTerrain>> levels = readStackFile(o.input);
  if (!levels) return fail(levels.error());
  if (o.level >= int(levels->size())) {
    return fail(makeError("{} has levels 0 to {}, not {}", o.input, levels->size() - 1, o.level));
  }
  const StackTerrain& terrain = (*levels)[std::size_t(o.level)];
  Result<QuantisedStacks> stacks =
      QuantisedStacks::from(terrain, o.cellM > 0.0 ? o.cellM : terrain.spacingM());
  if (!stacks) return fail(stacks.error());
  levels->clear();

  auto start = Clock::now();
  const NodeGrid grid = NodeGrid::of(stacks.value(), o.params);
  const std::vector<NodeKey> surface = nodesWithSurface(stacks.value(), o.params);
  const double selectS = secondsSince(start);
  const std::vector<NodeKey> nodes = sampleNodes(surface, o.nodes);
  fmt::print("{} level {}: {} x {} stacks at {:.3g} m, {} cells of {:.3g} m high; {} x {} x {} "
             "nodes of {}^3 cells ({} smoothing, r = {}), {} with a surface (found in {:.2f} s); "
             "running {}\n",
             o.input, o.level, stacks->width, stacks->height, stacks->spacingM, stacks->cellsZ,
             stacks->cellM, grid.nodesX, grid.nodesY, grid.nodesZ, o.params.nodeCells, o.filter,
             o.params.filterRadius, surface.size(), selectS, nodes.size());
  nlohmann::json out{{"input", o.input},
                     {"level", o.level},
                     {"stacks", {stacks->width, stacks->height}},
                     {"spacing_m", stacks->spacingM},
                     {"cell_m", stacks->cellM},
                     {"node_cells", o.params.nodeCells},
                     {"filter", o.filter},
                     {"radius", o.params.filterRadius},
                     {"nodes_total", grid.count()},
                     {"nodes_with_surface", surface.size()},
                     {"nodes_run", nodes.size()}};
  const double perNode = nodes.empty() ? 0.0 : 1.0 / double(nodes.size());

  std::size_t cpuQuads = 0, cpuVertices = 0;
  if (!o.noCpu) {
    QuadStageTimes times;
    start = Clock::now();
    StackMesh mesh = quadrangulateNodes(stacks.value(), o.params, nodes, &times);
    const double wallS = secondsSince(start);
    cpuQuads = mesh.quadCount();
    cpuVertices = mesh.vertices.size();
    const StackMeshCheck check = checkStackMesh(mesh);
    std::array<double, kMaterialChannels> share{};
    for (const StackVertex& v : mesh.vertices) {
      for (int m = 0; m < kMaterialChannels; ++m) share[std::size_t(m)] += v.materials[std::size_t(m)];
    }
    for (double& x : share) x /= std::max<double>(1.0, double(mesh.vertices.size()));
    fmt::print("CPU reference ({} threads): {:.0f} nodes/s, {:.1f} quads and {:.1f} vertices a "
               "node\n  per node, one thread: {}\n",
               tbb::this_task_arena::max_concurrency(), double(nodes.size()) / wallS,
               double(cpuQuads) * perNode, double(cpuVertices) * perNode, stagesLine(times, perNode));
    fmt::print("  mesh: {} quads, {} welded vertices, {} unbalanced edges{}, {} non-manifold "
               "edges, Euler characteristic {}\n",
               check.quads, check.vertices, check.unbalancedEdges,
               o.nodes == 0 ? " (0: closed)" : " (a sample of nodes is not closed)",
               check.nonManifoldEdges, check.eulerCharacteristic());
    fmt::print("  surface materials (mean vertex weight): rock {:.3f}, soil {:.3f}, grass {:.3f}, "
               "other {:.3f}\n",
               share[0], share[1], share[2], share[3]);
    out["cpu"] = {{"threads", tbb::this_task_arena::max_concurrency()},
                  {"wall_s", wallS},
                  {"nodes_per_s", double(nodes.size()) / wallS},
                  {"ms_per_node", stagesJson(times, perNode)},
                  {"quads", cpuQuads},
                  {"vertices", cpuVertices},
                  {"welded_vertices", check.vertices},
                  {"unbalanced_edges", check.unbalancedEdges},
                  {"non_manifold_edges", check.nonManifoldEdges},
                  {"euler_characteristic", check.eulerCharacteristic()},
                  {"surface_materials", share}};
  }

  if (!o.noGpu) {
    Result<std::unique_ptr<gl::GlContext>> context = createContext("headless");
    if (!context) return fail(context.error());
    Result<StackQuadPipelineGpu> gpu = StackQuadPipelineGpu::create(stacks.value(), o.params, o.batch);
    if (!gpu) return fail(gpu.error());
    if (Status ran = gpu->run(nodes); !ran) return fail(ran.error());  // sizes the buffers
    gl::finish();
    start = Clock::now();
    if (Status ran = gpu->run(nodes); !ran) return fail(ran.error());
    gl::finish();
    const double wallS = secondsSince(start);
    if (Status ran = gpu->run(nodes, true); !ran) return fail(ran.error());
    const QuadStageTimes times = gpu->stageTimes();
    const auto* device = reinterpret_cast<const char*>(glGetString(GL_RENDERER));
    fmt::print("GPU pipeline on {} ({} nodes a dispatch): {:.0f} nodes/s, {:.1f} quads a node\n"
               "  per node: {}\n",
               device, o.batch, double(nodes.size()) / wallS, double(gpu->indexCount() / 6) * perNode,
               stagesLine(times, perNode));
    const bool same = o.noCpu || (gpu->indexCount() / 6 == cpuQuads && gpu->vertexCount() == cpuVertices);
    if (!o.noCpu) {
      fmt::print("  {} the CPU reference's counts ({} quads, {} vertices)\n",
                 same ? "equal to" : "DIFFERENT FROM", gpu->indexCount() / 6, gpu->vertexCount());
    }
    out["gpu"] = {{"device", device},
                  {"batch", o.batch},
                  {"wall_s", wallS},
                  {"nodes_per_s", double(nodes.size()) / wallS},
                  {"ms_per_node", stagesJson(times, perNode)},
                  {"quads", gpu->indexCount() / 6},
                  {"vertices", gpu->vertexCount()},
                  {"equal_to_cpu", same}};
    if (!same) {
      return fail(makeError("the GPU pipeline's mesh differs from the CPU reference's"));
    }
  }
  if (!o.json.empty()) {
    Status written = writeTextFileAtomically(o.json, out.dump(2) + "\n");
    if (!written) return fail(written.error());
  }
  return 0;
}

}  // namespace tellus::cli
