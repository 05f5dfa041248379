#include "tellus/eval/renderer_registry.hpp"

#include <fmt/format.h>

#include "tellus/render/reference_renderer.hpp"
#include "tellus/render/rings_renderer.hpp"

namespace tellus {

std::vector<std::string_view> rendererNames() {
  return {"reference",        "rings", "rings-noculling", "rings-brute", "rings-brute-noculling",
          "rings-incremental"};
}

bool rendererNeedsStore(std::string_view name) {
  return name.starts_with("rings");
}

double rendererBytesPerSample(std::string_view name) {
  return name == "reference" ? 8.0 : 0.0;
}

Result<std::unique_ptr<TerrainRenderer>> makeRenderer(std::string_view name,
                                                      const RendererInputs& inputs) {
  const std::vector<std::string_view> names = rendererNames();
  if (std::find(names.begin(), names.end(), name) == names.end()) {
    return makeError("unknown renderer '{}' (available: {})", name, fmt::join(names, ", "));
  }
  if (name == "reference") {
    if (!inputs.grid) return makeError("the reference renderer needs the height grid");
    Result<ReferenceRenderer> renderer = ReferenceRenderer::create(*inputs.grid);
    if (!renderer) return renderer.error();
    return std::unique_ptr<TerrainRenderer>(
        std::make_unique<ReferenceRenderer>(std::move(renderer.value())));
  }
  if (!inputs.store) {
    return makeError(
        "renderer '{}' streams from a tile store: give a .tstore as input (make one "
        "with 'tellus build DEM... -o NAME.tstore')",
        name);
  }
  RingsOptions options = inputs.rings;
  options.name = std::string(name);
  options.frustumCulling = !name.ends_with("-noculling");
  options.bruteForce = name.starts_with("rings-brute");
  options.waitForTiles = inputs.waitForTiles;
  options.incrementalFractal = name == "rings-incremental";
  Result<std::unique_ptr<RingsRenderer>> rings = RingsRenderer::create(inputs.store, options);
  if (!rings) return rings.error();
  return std::unique_ptr<TerrainRenderer>(std::move(rings.value()));
}

}  // namespace tellus
