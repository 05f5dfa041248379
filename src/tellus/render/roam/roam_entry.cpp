// Seed 004's survey baseline ROAM (`--algo roam`): row, options, create().
#include "tellus/render/registry/renderer_registry.hpp"
#include "tellus/render/roam/roam_renderer.hpp"

namespace tellus {
namespace {

Result<std::unique_ptr<TerrainRenderer>> createRoam(const RendererEntry& entry,
                                                    const RendererInputs& inputs,
                                                    const std::any& given) {
  if (!inputs.grid) return makeError("renderer '{}' needs the height grid", entry.name);
  RoamOptions options = std::any_cast<const RoamOptions&>(given);
  options.name = std::string(entry.name);
  return madeRenderer(RoamRenderer::create(*inputs.grid, options));
}

OptionSchema roamSchema() {
  using O = RoamOptions;
  OptionSchema schema{"roam", "ROAM", defaultsOf<O>(), {}};
  RendererOption target = numberOption<O>(
      "--roam-target", "error target", "roam: error target, pixels (split above it, merge below it)",
      "px", 0.01, 1000.0, [](O& o) -> float& { return o.settings.targetPx; });
  target.panelMin = 0.1;
  target.panelMax = 20.0;
  target.live = true;
  RendererOption budget = numberOption<O>(
      "--roam-budget", "triangle budget", "roam: most triangles (leaves) a frame", "", 2,
      100000000, [](O& o) -> std::uint32_t& { return o.settings.triangleBudget; });
  budget.panelMin = 1000;
  budget.panelMax = 4'000'000;
  budget.live = true;
  RendererOption time = numberOption<O>(
      "--roam-time", "time budget",
      "roam: most milliseconds of splits and merges a frame (0: no limit)", "ms", 0.0, 100000.0,
      [](O& o) -> double& { return o.settings.timeBudgetMs; });
  time.panelMax = 50.0;
  time.live = true;
  RendererOption block = numberOption<O>(
      "--roam-block", "block 2^N cells",
      "roam: bintree blocks of 2^N cells a side (error bounds are kept per block)", "", 2, 10,
      [](O& o) -> int& { return o.settings.blockLog2; });
  block.panelMin = 4;
  block.panelMax = 9;
  schema.options = {target, budget, time, block};
  return schema;
}

// The target and budgets take effect in the next frame: the bintree adapts to them.
void applyLiveRoam(TerrainRenderer& renderer, const std::any& given) {
  auto* roam = dynamic_cast<RoamRenderer*>(&renderer);
  if (!roam) return;
  const roam::RoamSettings& wanted = std::any_cast<const RoamOptions&>(given).settings;
  roam::RoamSettings& live = roam->mesh().settings();
  live.targetPx = wanted.targetPx;
  live.triangleBudget = wanted.triangleBudget;
  live.timeBudgetMs = wanted.timeBudgetMs;
}

}  // namespace

const RendererFamily& roamRenderers() {
  static const RendererFamily family{
      roamSchema(),
      {{"roam",
        "ROAM: a triangle bintree split and merged on the CPU by two priority queues carried "
        "from frame to frame, nested error bounds, forced splits; the mesh streamed each frame",
        "004", RendererSource::HeightGrid, 6.0, createRoam}},
      applyLiveRoam,
      "the vertical distance from its mesh to the height texture under each pixel"};
  return family;
}

}  // namespace tellus
