// Seed 004's survey baseline, GPU geometry clipmaps (`--algo clipmaps`): row, options, create().
#include "tellus/render/clipmaps/clipmap_renderer.hpp"
#include "tellus/render/registry/renderer_registry.hpp"

namespace tellus {
namespace {

Result<std::unique_ptr<TerrainRenderer>> createClipmaps(const RendererEntry& entry,
                                                        const RendererInputs& inputs,
                                                        const std::any& given) {
  if (!inputs.store) {
    return makeError("renderer '{}' reads its levels from a tile store: give a .tstore as input "
                     "(make one with 'tellus build DEM... -o NAME.tstore')",
                     entry.name);
  }
  ClipmapOptions options = std::any_cast<const ClipmapOptions&>(given);
  options.name = std::string(entry.name);
  return madeRenderer(ClipmapRenderer::create(inputs.store, options));
}

OptionSchema clipmapSchema() {
  using O = ClipmapOptions;
  OptionSchema schema{"clipmaps", "Clipmaps", defaultsOf<O>(), {}};
  // Any number on the command line, so that the renderer's own check says what is wrong.
  RendererOption size = numberOption<O>(
      "--clipmap-size", "level size", "clipmaps: vertices a level side, 4m - 1 (31 to 1023)", "",
      31, 1023, [](O& o) -> int& { return o.n; });
  size.panelSteps = {31, 63, 127, 255, 303, 511, 1023};
  RendererOption levels = numberOption<O>(
      "--clipmap-levels", "levels",
      "clipmaps: levels (default: enough for the coarsest to span twice the terrain)", "", 1, 24,
      [](O& o) -> int& { return o.levels; });
  levels.autoDefault = true;
  levels.panelMin = 0;
  levels.panelMax = 16;
  RendererOption transition = numberOption<O>(
      "--clipmap-transition", "transition",
      "clipmaps: width of the geomorph band at each level's border, level units (default: a "
      "fifth of the level size; at most (size + 1) / 4 - 3.5)",
      "", 1.0, 256.0, [](O& o) -> float& { return o.transitionWidth; });
  transition.autoDefault = true;
  transition.panelMin = 0.0;
  transition.panelMax = 60.0;
  RendererOption noCulling = flagOption<O>(
      "--clipmap-no-culling", "no culling", "clipmaps: draw every block, also outside the view",
      [](O& o) -> bool& { return o.culling; }, false);
  RendererOption storedLevels = flagOption<O>(
      "--clipmap-stored-levels", "stored levels",
      "clipmaps: draw the store's subsampled levels, as the papers do, instead of levels "
      "prefiltered by least squares",
      [](O& o) -> bool& { return o.prefilter; }, false);
  schema.options = {size, levels, transition, noCulling, storedLevels};
  return schema;
}

}  // namespace

const RendererFamily& clipmapRenderers() {
  static const RendererFamily family{
      clipmapSchema(),
      {{"clipmaps",
        "GPU geometry clipmaps: nested grids centred on the viewer, heights in toroidal textures "
        "updated from the tile store as it moves, geomorphing at level borders",
        "004", RendererSource::TileStore, 0.0, createClipmaps}},
      {},
      "the geometric error of each level's pyramid level, blended across the transition bands"};
  return family;
}

}  // namespace tellus
