#include "tellus/render/drawing/grid_index_buffers.hpp"

#include <cstdint>
#include <span>
#include <vector>

namespace tellus {

const gl::Buffer& GridIndexBuffers::forGrid(int vertsX, int vertsY) {
  const auto key = std::make_pair(vertsX, vertsY);
  auto found = buffers_.find(key);
  if (found != buffers_.end()) return found->second;
  std::vector<std::uint32_t> indices;
  indices.reserve(std::size_t(vertsX - 1) * std::size_t(vertsY - 1) * 6);
  for (int r = 0; r + 1 < vertsY; ++r) {
    for (int c = 0; c + 1 < vertsX; ++c) {
      const auto v00 = std::uint32_t(r * vertsX + c), v10 = v00 + 1;
      const auto v01 = std::uint32_t((r + 1) * vertsX + c), v11 = v01 + 1;
      indices.insert(indices.end(), {v00, v01, v10, v10, v01, v11});
    }
  }
  return buffers_.emplace(key, gl::Buffer(std::span<const std::uint32_t>(indices))).first->second;
}

}  // namespace tellus
