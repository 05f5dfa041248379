// Seed 003's stack terrain (`--algo stacks-full`, `stacks`): rows, options, create().
#include "tellus/render/registry/renderer_registry.hpp"
#include "tellus/render/stacks/stacks_full_renderer.hpp"
#include "tellus/render/stacks/stacks_lod_renderer.hpp"

namespace tellus {
namespace {

Status needStacks(const RendererEntry& entry, const RendererInputs& inputs) {
  if (!inputs.stacks || inputs.stacks->empty()) {
    return makeError("renderer '{}' draws material stacks: give a .tstack as input (make one with "
                     "'tellus stacks build DEM -o NAME.tstack')",
                     entry.name);
  }
  return {};
}

Result<std::unique_ptr<TerrainRenderer>> createStacksFull(const RendererEntry& entry,
                                                          const RendererInputs& inputs,
                                                          const std::any& given) {
  if (Status ok = needStacks(entry, inputs); !ok) return ok.error();
  return madeRenderer(StacksFullRenderer::create(inputs.stacks->front(),
                                                 std::any_cast<const StacksRenderOptions&>(given)));
}

Result<std::unique_ptr<TerrainRenderer>> createStacksLod(const RendererEntry& entry,
                                                         const RendererInputs& inputs,
                                                         const std::any& given) {
  if (Status ok = needStacks(entry, inputs); !ok) return ok.error();
  return madeRenderer(StacksLodRenderer::create(
      *inputs.stacks, std::any_cast<const StacksRenderOptions&>(given), inputs.waitForTiles));
}

OptionSchema stackSchema() {
  using O = StacksRenderOptions;
  OptionSchema schema{"stacks", "Stacks", defaultsOf<O>(), {}};
  RendererOption nodeCells = numberOption<O>(
      "--stack-node-cells", "node cells", "Stack renderers: cells per node side (the seed: 17)", "",
      3, 64, [](O& o) -> int& { return o.quad.nodeCells; });
  nodeCells.panelMin = 5;
  nodeCells.panelMax = 33;
  RendererOption filter = choiceOption<O, SmoothingFilter>(
      "--stack-filter", "smoothing", "Stack renderers: smoothing filter",
      {{"gauss", SmoothingFilter::Gauss}, {"box", SmoothingFilter::Box}},
      [](O& o) -> SmoothingFilter& { return o.quad.filter; });
  RendererOption radius = numberOption<O>(
      "--stack-radius", "smoothing radius",
      "Stack renderers: smoothing radius r (2r + 1 taps), 0 to 4", "", 0, 4,
      [](O& o) -> int& { return o.quad.filterRadius; });
  RendererOption cell = numberOption<O>(
      "--stack-cell-m", "cell height",
      "Stack renderers: density cell height (default: the stack spacing)", "m", 0.01, 10000.0,
      [](O& o) -> double& { return o.cellM; });
  cell.autoDefault = true;
  cell.inPanel = false;
  RendererOption tau = numberOption<O>(
      "--stack-tau", "tau", "stacks: split a node while its cells span more pixels than this (the seed: 10)",
      "px", 0.1, 10000.0, [](O& o) -> double& { return o.tauPx; });
  tau.panelMin = 1.0;
  tau.panelMax = 40.0;
  RendererOption errorTau = numberOption<O>(
      "--stack-error-tau", "error tau",
      "stacks: also split while a node's geometric error (cave roofs and passages its level "
      "loses) spans more pixels than this; 0: the seed's criterion alone",
      "px", 0.0, 10000.0, [](O& o) -> double& { return o.errorTauPx; });
  errorTau.panelMax = 100.0;
  RendererOption updates = numberOption<O>(
      "--stack-updates", "updates / frame",
      "stacks: node quadrangulations a frame at most, 0 for no limit (the seed: ~40)", "", 0,
      100000, [](O& o) -> int& { return o.updatesPerFrame; });
  updates.panelMax = 200;
  RendererOption burst = numberOption<O>(
      "--stack-burst", "burst / frame",
      "stacks: node quadrangulations a frame at most when the drawn selection is far too coarse "
      "for the view (the lag bound makes the whole new selection), 0 for no limit",
      "", 0, 1000000, [](O& o) -> int& { return o.burstPerFrame; });
  burst.panelMax = 8192;
  RendererOption morph = numberOption<O>(
      "--stack-morph-frames", "geomorph frames",
      "stacks: geomorph a split or merge over this many frames, 0 to switch at once as the seed "
      "does",
      "", 0, 120, [](O& o) -> int& { return o.morphFrames; });
  morph.panelMax = 30;
  RendererOption seam = numberOption<O>(
      "--stack-seam-band", "seam band",
      "stacks: next to a coarser node, take the coarser surface over this many cells (no step "
      "at level borders; at most (node cells - 1) / 2 - 1), 0 for the seed's stitching alone",
      "cells", 0, 31, [](O& o) -> int& { return o.seamBandCells; });
  seam.panelMax = 7;
  RendererOption pool = numberOption<O>(
      "--stack-pool-mib", "mesh pool", "stacks: GPU mesh cache size", "MiB", 1, 16384,
      [](O& o) -> int& { return o.poolMiB; });
  pool.panelMin = 16;
  pool.panelMax = 4096;
  schema.options = {nodeCells, filter, radius, cell, tau, errorTau, updates, burst, morph, seam, pool};
  return schema;
}

}  // namespace

const RendererFamily& stackRenderers() {
  static const RendererFamily family{
      stackSchema(),
      {{"stacks-full",
        "material stacks with arches, overhangs and caves quadrangulated whole at the finest "
        "level on the GPU (density, smoothing, dual contouring), one indirect draw: the 3D "
        "ground truth",
        "003", RendererSource::StackTerrain, 0.0, createStacksFull},
       {"stacks",
        "octree LOD over the stack MipMap: nodes by screen-space extent, stitched across levels, "
        "meshes cached in one GPU pool (LRU), made by the GPU pipeline at most K a frame",
        "003", RendererSource::StackTerrain, 0.0, createStacksLod}},
      {},
      {}};
  return family;
}

}  // namespace tellus
