// Seed 004's GAMeR (`--algo gamer`): row, options, create().
#include "tellus/render/gamer/gamer_renderer.hpp"
#include "tellus/render/registry/renderer_registry.hpp"

namespace tellus {
namespace {

Result<std::unique_ptr<TerrainRenderer>> createGamer(const RendererEntry& entry,
                                                     const RendererInputs& inputs,
                                                     const std::any& given) {
  if (!inputs.grid) return makeError("renderer '{}' needs the height grid", entry.name);
  GamerOptions options = std::any_cast<const GamerOptions&>(given);
  options.name = std::string(entry.name);
  return madeRenderer(GamerRenderer::create(*inputs.grid, options));
}

OptionSchema gamerSchema() {
  using O = GamerOptions;
  OptionSchema schema{"gamer", "GAMeR", defaultsOf<O>(), {}};
  RendererOption target = numberOption<O>(
      "--gamer-target", "error target", "gamer: error target of the depth tags, pixels", "px",
      0.01, 1000.0, [](O& o) -> float& { return o.settings.targetPx; });
  target.panelMin = 0.1;
  target.panelMax = 20.0;
  target.live = true;
  RendererOption depth = numberOption<O>(
      "--gamer-depth", "pattern depth",
      "gamer: deepest pattern, 2^N segments a coarse edge (coarse cells of 2^N samples)", "", 2,
      gamer::kMaxPatternDepth, [](O& o) -> int& { return o.settings.maxDepth; });
  RendererOption noCulling = flagOption<O>(
      "--gamer-no-culling", "no culling", "gamer: draw every coarse triangle, also outside the view",
      [](O& o) -> bool& { return o.settings.culling; }, false);
  RendererOption morph = numberOption<O>(
      "--gamer-morph", "morph band",
      "gamer: geomorph, the share of each depth's distance range over which its new vertices slide "
      "from the coarser surface (0: none, whole patterns pop)",
      "", 0.0, 1.0, [](O& o) -> float& { return o.settings.morphBand; });
  morph.live = true;
  schema.options = {target, depth, morph, noCulling};
  return schema;
}

// The target and morph band apply from the next frame: the tags follow them.
void applyLiveGamer(TerrainRenderer& renderer, const std::any& given) {
  if (auto* gamer = dynamic_cast<GamerRenderer*>(&renderer)) {
    const gamer::GamerSettings& settings = std::any_cast<const GamerOptions&>(given).settings;
    gamer->setTargetPx(settings.targetPx);
    gamer->setMorphBand(settings.morphBand);
  }
}

}  // namespace

const RendererFamily& gamerRenderers() {
  static const RendererFamily family{
      gamerSchema(),
      {{"gamer",
        "GAMeR: depth tags at the coarse vertices from distance and local error, a precomputed "
        "refinement pattern per coarse triangle (one per edge-depth triple), instanced by one "
        "multi-draw-indirect, heights from the grid texture",
        "004", RendererSource::HeightGrid, 4.0, createGamer}},
      applyLiveGamer,
      "the vertical distance from its mesh to the height texture under each pixel"};
  return family;
}

}  // namespace tellus
