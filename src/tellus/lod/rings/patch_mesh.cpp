#include "tellus/lod/rings/patch_mesh.hpp"

#include <bit>

#include "tellus/lod/rings/rings_structure.hpp"

namespace tellus {

Result<PatchMesh> buildPatchMesh(int cells) {
  if (cells < 1 || cells > 4096 || !std::has_single_bit(unsigned(cells))) {
    return makeError("patch mesh cells must be a power of two in 1..4096, got {}", cells);
  }
  PatchMesh mesh;
  mesh.cells = cells;
  const int side = cells + 1;
  mesh.vertices.reserve(std::size_t(side) * std::size_t(side));
  for (int z = 0; z <= cells; ++z) {
    for (int x = 0; x <= cells; ++x) {
      PatchVertex v;
      v.x = std::uint16_t(x);
      v.z = std::uint16_t(z);
      if (z == 0) v.edges |= kEdgeUp;
      if (x == cells) v.edges |= kEdgeRight;
      if (z == cells) v.edges |= kEdgeDown;
      if (x == 0) v.edges |= kEdgeLeft;
      // Along the up/down edges the position is x, along the left/right edges z; a corner is
      // even on both.
      const bool horizontalEdge = (v.edges & (kEdgeUp | kEdgeDown)) != 0;
      const bool verticalEdge = (v.edges & (kEdgeLeft | kEdgeRight)) != 0;
      if (horizontalEdge != verticalEdge) {
        v.odd = std::uint16_t(((horizontalEdge ? x : z) & 1) != 0);
      }
      mesh.vertices.push_back(v);
    }
  }
  mesh.indices.reserve(std::size_t(cells) * std::size_t(cells) * 6);
  for (int z = 0; z < cells; ++z) {
    for (int x = 0; x < cells; ++x) {
      const auto v00 = std::uint32_t(z * side + x), v10 = v00 + 1;
      const auto v01 = std::uint32_t((z + 1) * side + x), v11 = v01 + 1;
      // Counter-clockwise seen from above (x east, z south, up out of the page).
      mesh.indices.insert(mesh.indices.end(), {v00, v01, v10, v10, v01, v11});
    }
  }
  return mesh;
}

glm::ivec2 stitchedPosition(const PatchVertex& vertex, std::uint8_t stitchEdges) {
  glm::ivec2 p(vertex.x, vertex.z);
  if (vertex.odd == 0 || (vertex.edges & stitchEdges) == 0) return p;
  if ((vertex.edges & (kEdgeUp | kEdgeDown)) != 0) {
    p.x -= 1;  // along a horizontal edge: the previous even vertex is to the west
  } else {
    p.y -= 1;  // along a vertical edge: the previous even vertex is to the north
  }
  return p;
}

}  // namespace tellus
