#pragma once
// The static patch meshes of seed 000 (GL-free): one flat grid per level of detail, built once
// before the render loop and displaced by the vertex shader. Every vertex carries the seed's
// 4-tuple (x, z, position flag, odd flag):
//   x, z       grid coordinates in [0, cells] (x east, z south: row 0 is the patch's north edge)
//   edges      position flag: the patch edges the vertex lies on, as PatchEdge bits
//              (0 = interior, one bit = edge vertex, two bits = corner vertex)
//   odd        1 when the vertex sits at an odd position along its edge (corners are even)
//
// Stitching (the vertex shader's rule, with stitchedPosition() its CPU twin): on an edge that
// meets a coarser neighbour (a bit of the patch's stitch mask), an odd edge vertex is moved
// onto the previous even vertex of that edge, so the edge has exactly the coarser neighbour's
// vertices; the triangles touching the moved vertex become degenerate or stretch, leaving no
// crack and no T-junction.
#include <cstdint>
#include <vector>

#include <glm/vec2.hpp>

#include "tellus/core/result.hpp"

namespace tellus {

struct PatchVertex {
  std::uint16_t x = 0, z = 0;
  std::uint16_t edges = 0;  // PatchEdge bits
  std::uint16_t odd = 0;    // 0 or 1
};
static_assert(sizeof(PatchVertex) == 8, "uploaded as four unsigned shorts");

struct PatchMesh {
  int cells = 0;  // grid cells per side; (cells + 1)^2 vertices
  std::vector<PatchVertex> vertices;
  std::vector<std::uint32_t> indices;  // triangles, two per cell
  std::uint64_t triangleCount() const { return indices.size() / 3; }
};

// cells: a power of two >= 1.
Result<PatchMesh> buildPatchMesh(int cells);

// Where the vertex shader draws `vertex` of a patch whose edges in `stitchEdges` meet a coarser
// neighbour: its own grid position, or the previous even vertex of a stitched edge.
glm::ivec2 stitchedPosition(const PatchVertex& vertex, std::uint8_t stitchEdges);

}  // namespace tellus
