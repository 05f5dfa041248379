#pragma once
// BDAM's leaves at the grid's full resolution (beyond the seed, issue 45): a leaf patch is
// simplified (8 times fewer triangles than the grid at the default leaf size), so a viewer a
// few metres above the ground sees metres of error, or the patch above its eye. When a leaf's
// diamond still asks for more detail than its patch has, the renderer draws the leaf "exact":
// every grid cell inside the leaf's triangle, split along its south-west / north-east diagonal
// as the reference renderer draws the grid, made from the grid at run time (not stored).
//
// Crack-free: the leaves' legs keep every sample (bdam_patches.hpp), and an exact leaf's edges
// keep every sample too, so an exact leaf meets a simplified neighbour across a leg. Across its
// hypotenuse the neighbour is its mate (one diamond: both exact) or a coarser patch, which a
// conforming cut never leaves beside a refining diamond (bdam_selection.hpp).
//
// The reference's diagonal: a leaf edge at 45 degrees cuts the cells along it in half. Along a
// south-west / north-east edge that is the reference's own cut. Along a north-west / south-east
// edge (a triangle has at most one), the halves would cross the reference's diagonal; when the
// leaf across that edge is drawn exact too, one of the two (the lower node id) draws those cells
// whole, split the reference's way, and the other leaves them out. Otherwise each draws its half.
//
// Coordinates as in bdam_bintree.hpp: grid samples, x east, y north of the southern row.
#include <cstdint>
#include <vector>

#include <glm/vec2.hpp>

#include "tellus/dem/height_grid.hpp"
#include "tellus/formats/bdam/bdam_bintree.hpp"
#include "tellus/formats/bdam/bdam_file.hpp"

namespace tellus::bdam {

// What an exact leaf draws of the cells its north-west / south-east edge cuts in half.
enum class CutCells : std::uint8_t {
  Half = 0,   // its half of each (the neighbour is not drawn exact)
  Whole = 1,  // the whole cells, split the reference's way (it owns them)
  None = 2,   // none (the exact neighbour owns them)
};

struct ExactLeafMesh {
  glm::uvec2 origin{0};                 // the triangle's south-west box corner, samples
  std::vector<PackedVertex> vertices;   // relative to origin, heights from the grid
  std::vector<std::uint16_t> indices;   // counter-clockwise seen from above
  float minZ = 0.0f, maxZ = 0.0f;       // of the vertices, metres
};

// The triangle's edge that runs north-west / south-east, as its two end points; false when none
// does (the hypotenuse or legs are axis-aligned or south-west / north-east).
bool northwestEdge(const Triangle& t, glm::ivec2& a, glm::ivec2& b);

// The node of level `level` across the edge (a, b) of `t` (a point just outside the edge's
// midpoint, located in the bintree). Nodes outside the domain: 0.
NodeId nodeAcross(const Triangle& t, glm::ivec2 a, glm::ivec2 b, int level, int domainLog2);

// The exact mesh of `leaf`: the grid's cells (those inside the grid) inside its triangle, split
// south-west / north-east, and the cells its north-west / south-east edge cuts as `cut` says.
// Vertices are the grid samples the triangles use. The caller keeps leaves under 65,536
// vertices (bdam_patches.hpp allows leaves of at most 2^16 half-cells: about 33,000 vertices).
ExactLeafMesh exactLeafMesh(const HeightGrid& grid, NodeId leaf, int domainLog2, CutCells cut);

}  // namespace tellus::bdam
