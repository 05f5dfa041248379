// `--algo globe-reference`: every sample of a lat/lon DEM on the ellipsoid, the globe's ground
// truth. No options (the geoid and the drape are inputs).
#include "tellus/render/globe/globe_reference_renderer.hpp"
#include "tellus/render/registry/renderer_registry.hpp"

namespace tellus {
namespace {

struct NoOptions {};

Result<std::unique_ptr<TerrainRenderer>> createGlobeReference(const RendererEntry& entry,
                                                              const RendererInputs& inputs,
                                                              const std::any&) {
  if (!inputs.grid) return makeError("renderer '{}' needs the height grid", entry.name);
  Result<GlobeReferenceRenderer> renderer =
      GlobeReferenceRenderer::create(*inputs.grid, inputs.geoid, inputs.drape);
  if (!renderer) return renderer.error();
  return std::unique_ptr<TerrainRenderer>(
      std::make_unique<GlobeReferenceRenderer>(std::move(renderer.value())));
}

}  // namespace

const RendererFamily& globeReferenceRenderers() {
  static const RendererFamily family{
      {"globe-reference", "Globe reference", defaultsOf<NoOptions>(), {}},
      {{"globe-reference",
        "every sample of a lat/lon DEM on the WGS84 ellipsoid, no LOD: the globe's ground truth",
        "-", RendererSource::HeightGrid, 112.0, createGlobeReference, RendererWorld::Globe}},
      {},
      {}};
  return family;
}

}  // namespace tellus
