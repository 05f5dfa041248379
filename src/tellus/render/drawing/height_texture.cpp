#include "tellus/render/drawing/height_texture.hpp"

#include <optional>

#include <spdlog/spdlog.h>

#include "tellus/lod/rag/rag_height_map.hpp"

namespace tellus {

ShadingHeightTexture ShadingHeightTexture::create(const HeightGrid& grid, std::string_view who) {
  ShadingHeightTexture out;
  GLint maxTexture = 0;
  glGetIntegerv(GL_MAX_TEXTURE_SIZE, &maxTexture);
  const int level = rag::heightMapLevel(grid.width, grid.height, int(maxTexture));
  std::optional<rag::HeightMap> coarser;
  if (level > 0) {
    coarser = rag::heightMapAtLevel(grid, level);
    out.errorM = coarser->errorM;
    out.stride = 1 << level;
    spdlog::info("{}: shading from level {} of the grid ({} x {}: beyond the texture limit)", who, level,
                 grid.width, grid.height);
  }
  const HeightGrid& map = coarser ? coarser->grid : grid;
  out.texture = gl::Texture::create2D(GL_R32F, map.width, map.height);
  out.texture.upload2D(0, 0, 0, map.width, map.height, GL_RED, GL_FLOAT, map.heights.data());
  out.texture.setFilter(GL_LINEAR, GL_LINEAR);
  out.texture.setWrap(GL_CLAMP_TO_EDGE);
  return out;
}

}  // namespace tellus
