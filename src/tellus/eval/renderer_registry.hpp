#pragma once
// The renderers `--algo NAME` can pick, by name. Each is created for one terrain; LOD renderers
// that stream from a tile store will receive it here as they land.
#include <memory>
#include <string_view>
#include <vector>

#include "tellus/core/result.hpp"
#include "tellus/dem/height_grid.hpp"
#include "tellus/render/terrain_renderer.hpp"

namespace tellus {

std::vector<std::string_view> rendererNames();

// Needs a current GL context. Errors name the valid choices.
Result<std::unique_ptr<TerrainRenderer>> makeRenderer(std::string_view name,
                                                      const HeightGrid& terrain);

}  // namespace tellus
