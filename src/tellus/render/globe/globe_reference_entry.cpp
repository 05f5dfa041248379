// `--algo globe-reference`: the globe's ground truth. From a lat/lon DEM (or a region of a global
// store read at one depth), every sample on the ellipsoid; from a global store, the cut of its
// tiles within `--globe-reference-px` of its finest data (the geoid and the drape are inputs).
#include "tellus/render/globe/globe_reference_renderer.hpp"
#include "tellus/render/registry/renderer_registry.hpp"

namespace tellus {
namespace {

struct GlobeReferenceOptions {
  double tolerancePx = GlobeReferenceRenderer::kDefaultStoreTolerancePx;
};

Result<std::unique_ptr<TerrainRenderer>> boxed(Result<GlobeReferenceRenderer> made) {
  if (!made) return made.error();
  return std::unique_ptr<TerrainRenderer>(
      std::make_unique<GlobeReferenceRenderer>(std::move(made.value())));
}

Result<std::unique_ptr<TerrainRenderer>> createGlobeReference(const RendererEntry& entry,
                                                              const RendererInputs& inputs,
                                                              const std::any& given) {
  const auto& options = std::any_cast<const GlobeReferenceOptions&>(given);
  if (inputs.grid) {
    return boxed(GlobeReferenceRenderer::create(*inputs.grid, inputs.geoid, inputs.drape));
  }
  if (inputs.globalStore) {
    return boxed(GlobeReferenceRenderer::create(inputs.globalStore, inputs.geoid, inputs.drape,
                                                options.tolerancePx));
  }
  return makeError("renderer '{}' needs a lat/lon DEM or a global store", entry.name);
}

OptionSchema globeReferenceSchema() {
  using O = GlobeReferenceOptions;
  OptionSchema schema{"globe-reference", "Globe reference", defaultsOf<O>(), {}};
  RendererOption tolerance = numberOption<O>(
      "--globe-reference-px", "tolerance",
      "globe reference on a global store: the screen-space error a tile shallower than the "
      "store's finest may have (deeper tiles where it would be more)",
      "px", 0.01, 10.0, [](O& o) -> double& { return o.tolerancePx; });
  tolerance.panelMin = 0.05;
  tolerance.panelMax = 2.0;
  schema.options = {tolerance};
  return schema;
}

}  // namespace

const RendererFamily& globeReferenceRenderers() {
  static const RendererFamily family{
      globeReferenceSchema(),
      {{"globe-reference",
        "every sample of a lat/lon DEM on the WGS84 ellipsoid, or a global store's finest tiles "
        "wherever they show, no LOD: the globe's ground truth",
        "-", RendererSource::HeightGrid, 112.0, createGlobeReference, RendererWorld::Globe}},
      {},
      {}};
  return family;
}

}  // namespace tellus
