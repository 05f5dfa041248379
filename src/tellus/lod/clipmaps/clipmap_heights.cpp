#include "tellus/lod/clipmaps/clipmap_heights.hpp"

#include <cmath>

namespace tellus::clipmaps {

float coarserSurfaceHeight(const LevelSampler& sampler, int level, glm::ivec2 v) {
  const int coarse = level + 1;
  const bool oddX = (v.x & 1) != 0, oddY = (v.y & 1) != 0;
  if (!oddX && !oddY) return sampler(coarse, halfFloor(v));
  glm::ivec2 a, b;
  if (oddX && !oddY) {
    a = {v.x - 1, v.y};
    b = {v.x + 1, v.y};
  } else if (!oddX && oddY) {
    a = {v.x, v.y - 1};
    b = {v.x, v.y + 1};
  } else {  // a coarse cell's centre, on its SW-NE diagonal (row grows southwards)
    a = {v.x - 1, v.y + 1};
    b = {v.x + 1, v.y - 1};
  }
  return 0.5f * (sampler(coarse, halfFloor(a)) + sampler(coarse, halfFloor(b)));
}

glm::vec2 texelHeights(const LevelSampler& sampler, const ClipmapShape& shape, int level, glm::ivec2 vertex) {
  const float own = sampler(level, vertex);
  if (level + 1 >= shape.levels) return {own, own};
  return {own, coarserSurfaceHeight(sampler, level, vertex)};
}

std::vector<glm::vec3> referenceMesh(const ClipmapShape& shape, const Footprints& footprints,
                                     const std::vector<glm::ivec2>& origins, glm::dvec2 viewer,
                                     const LevelSampler& sampler) {
  std::vector<glm::vec3> out;
  for (int level = 0; level < shape.levels; ++level) {
    const glm::ivec2 origin = origins[std::size_t(level)];
    const glm::ivec2 trim =
        level > 0 ? trimSide(shape, origin, origins[std::size_t(level - 1)]) : glm::ivec2(0);
    const double scale = std::ldexp(1.0, level);
    const glm::dvec2 viewerLevel = viewer / scale;
    for (const Piece* piece : piecesForLevel(footprints, shape, level, trim)) {
      for (std::uint32_t i = 0; i < piece->indexCount; ++i) {
        const std::uint32_t id = footprints.indices[piece->firstIndex + i];
        const glm::ivec2 vertex = origin + glm::ivec2(int(id) % shape.n, int(id) / shape.n);
        const glm::vec2 heights = texelHeights(sampler, shape, level, vertex);
        const float alpha = blendWeight(shape, vertex, viewerLevel);
        out.emplace_back(float(vertex.x * scale), float(vertex.y * scale),
                         heights.x + alpha * (heights.y - heights.x));
      }
    }
  }
  return out;
}

}  // namespace tellus::clipmaps
