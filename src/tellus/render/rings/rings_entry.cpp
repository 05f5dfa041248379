// Seed 000's rings (`--algo rings` and its Table 1 ablations): rows, options, create().
#include "tellus/render/registry/renderer_registry.hpp"
#include "tellus/render/rings/rings_renderer.hpp"

namespace tellus {
namespace {

Result<std::unique_ptr<TerrainRenderer>> createRings(const RendererEntry& entry,
                                                     const RendererInputs& inputs,
                                                     const std::any& given) {
  if (!inputs.store) {
    return makeError(
        "renderer '{}' streams from a tile store: give a .tstore as input (make one "
        "with 'tellus build DEM... -o NAME.tstore')",
        entry.name);
  }
  // The name, culling, brute force, waiting and incremental decoding follow from the row.
  RingsOptions options = std::any_cast<const RingsOptions&>(given);
  options.name = std::string(entry.name);
  options.frustumCulling = !entry.name.ends_with("-noculling");
  options.bruteForce = entry.name.starts_with("rings-brute");
  options.waitForTiles = inputs.waitForTiles;
  options.incrementalFractal = entry.name == "rings-incremental";
  return madeRenderer(RingsRenderer::create(inputs.store, options));
}

OptionSchema ringsSchema() {
  using O = RingsOptions;
  OptionSchema schema{"rings", "Rings", defaultsOf<O>(), {}};
  RendererOption patch = choiceOption<O, int>(
      "--rings-patch-cells", "patch cells",
      "rings: mesh cells per side of a finest patch (0: the tile size, a vertex per sample; the "
      "seed: 128 for 256-sample tiles)",
      {{"0", 0}, {"32", 32}, {"64", 64}, {"128", 128}, {"256", 256}, {"512", 512}},
      [](O& o) -> int& { return o.patchCells; });
  patch.aliases = {"--patch-cells"};
  RendererOption rings = numberOption<O>(
      "--rings-count", "rings", "rings: number of rings (0: enough to reach the whole terrain)",
      "", 0, 64, [](O& o) -> int& { return o.rings; });
  rings.aliases = {"--rings"};
  rings.panelMax = 32;
  RendererOption slots = numberOption<O>(
      "--rings-gpu-slots", "GPU cache slots",
      "rings: tiles the GPU cache holds (the seed's cache: 40)", "", 4, 4096,
      [](O& o) -> int& { return o.gpuSlots; });
  slots.aliases = {"--gpu-slots"};
  slots.panelMin = 8;
  slots.panelMax = 512;
  RendererOption uploads = numberOption<O>(
      "--rings-uploads", "uploads / frame", "rings: tile uploads per frame when streaming", "",
      1, 1024, [](O& o) -> int& { return o.maxUploadsPerFrame; });
  uploads.aliases = {"--uploads-per-frame"};
  uploads.panelMax = 64;
  schema.options = {patch, rings, slots, uploads};
  return schema;
}

}  // namespace

const RendererFamily& ringsRenderers() {
  static const RendererFamily family{
      ringsSchema(),
      {{"rings", "rings of patches around the viewer, GPU stitching, frustum culling", "000",
        RendererSource::TileStore, 0.0, createRings},
       {"rings-noculling", "rings without frustum culling (seed 000 Table 1)", "000",
        RendererSource::TileStore, 0.0, createRings, RendererWorld::Flat, true},
       {"rings-brute", "every patch at the finest level, with culling (seed 000 Table 1)", "000",
        RendererSource::TileStore, 0.0, createRings, RendererWorld::Flat, true},
       {"rings-brute-noculling", "every patch at the finest level, no culling (seed 000 Table 1)",
        "000", RendererSource::TileStore, 0.0, createRings, RendererWorld::Flat, true},
       {"rings-incremental",
        "rings on a fractal store, tiles decoded on the GPU with iterations by distance", "000",
        RendererSource::TileStore, 0.0, createRings, RendererWorld::Flat, true}},
      {},
      "the geometric error of the pyramid level each patch reads, an upper bound"};
  return family;
}

}  // namespace tellus
