// `--algo reference`: every sample as a vertex, the flat world's ground truth. No options.
#include "tellus/render/reference/reference_renderer.hpp"
#include "tellus/render/registry/renderer_registry.hpp"

namespace tellus {
namespace {

struct NoOptions {};

Result<std::unique_ptr<TerrainRenderer>> createReference(const RendererEntry& entry,
                                                         const RendererInputs& inputs,
                                                         const std::any&) {
  if (!inputs.grid) return makeError("renderer '{}' needs the height grid", entry.name);
  Result<ReferenceRenderer> renderer = ReferenceRenderer::create(*inputs.grid);
  if (!renderer) return renderer.error();
  return std::unique_ptr<TerrainRenderer>(
      std::make_unique<ReferenceRenderer>(std::move(renderer.value())));
}

}  // namespace

const RendererFamily& referenceRenderers() {
  static const RendererFamily family{
      {"reference", "Reference", defaultsOf<NoOptions>(), {}},
      {{"reference", "every sample as a vertex, no LOD, no culling: the ground truth", "-",
        RendererSource::HeightGrid, 8.0, createReference}},
      {},
      "zero everywhere: it draws every sample"};
  return family;
}

}  // namespace tellus
