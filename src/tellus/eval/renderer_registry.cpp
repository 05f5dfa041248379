#include "tellus/eval/renderer_registry.hpp"

#include <fmt/format.h>

#include "tellus/render/reference_renderer.hpp"

namespace tellus {

std::vector<std::string_view> rendererNames() {
  return {"reference"};
}

Result<std::unique_ptr<TerrainRenderer>> makeRenderer(std::string_view name,
                                                      const HeightGrid& terrain) {
  if (name == "reference") {
    Result<ReferenceRenderer> renderer = ReferenceRenderer::create(terrain);
    if (!renderer) return renderer.error();
    return std::unique_ptr<TerrainRenderer>(
        std::make_unique<ReferenceRenderer>(std::move(renderer.value())));
  }
  return makeError("unknown renderer '{}' (available: {})", name, fmt::join(rendererNames(), ", "));
}

}  // namespace tellus
