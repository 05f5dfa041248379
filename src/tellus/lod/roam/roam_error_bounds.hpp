#pragma once
// ROAM's nested error bounds ("wedgies", Duchaineau et al. 1997, section 5) over a height grid.
//
// The bintree's domain: the grid cut into square blocks of 2^blockLog2 cells, each block split
// along its SW-NE diagonal into two root triangles. A node of a root's bintree is named by its
// heap index (root 1, children 2i and 2i + 1) and lies at depth floor(log2 i); leaves, at depth
// 2 * blockLog2, are half cells. Coordinates are (u, v) samples: u east of the western column,
// v north of the southern row (RAG's convention; world x = u * spacingX, y = v * spacingY).
// Blocks on the east and north edges reach past the grid: heights there repeat the edge sample
// (clamping), and the mesh clamps such vertices onto the edge.
//
// The wedgie thickness of a node T with children T0, T1 and hypotenuse midpoint c is
//   e(T) = max(e(T0), e(T1)) + |z(c) - (z(l) + z(r)) / 2|,   e(leaf) = 0,
// so e(parent) >= e(child) (nesting) and the surface lies within e(T) of T's plane over T.
// The finest level is drawn as every reference grid draws it (the reference renderer, rings,
// the clipmaps, GAMeR: each cell split along its SW-NE diagonal), not along the bintree's
// alternating diagonals: RoamMesh::emit turns the diagonal of a cell whose half-cell leaves
// have a NW-SE hypotenuse (both halves of a cell are always leaves together, and their leg
// neighbours are half cells too, so the mesh stays conforming). The two triangulations of a
// cell differ by at most its twist |z(sw) + z(ne) - z(nw) - z(se)| / 2, so the nodes whose
// children are half cells add the twist of each turned child's cell to their own midpoint
// error (lastSplitBound), and the bounds above nest on that: they bound the surface drawn.
// Stored as uint16 in steps of kBoundStepM rounded up (conservative; a saturated value means
// "unbounded"), for depths up to 2 * blockLog2 - 2: the last level above the leaves is computed
// on the fly from its three samples. That is 2 bytes per sample for a whole block.
#include <array>
#include <cstdint>
#include <vector>

#include <glm/vec2.hpp>

#include "tellus/dem/height_grid.hpp"

namespace tellus::roam {

inline constexpr float kBoundStepM = 0.125f;

struct BintreeDomain {
  int blockLog2 = 7;  // cells a block side: 2^blockLog2
  int blocksX = 0, blocksY = 0;
  int gridWidth = 0, gridHeight = 0;  // samples

  static BintreeDomain forGrid(int gridWidth, int gridHeight, int blockLog2);
  int blockCells() const { return 1 << blockLog2; }
  int leafDepth() const { return 2 * blockLog2; }
  int blockCount() const { return blocksX * blocksY; }
  // Stored bounds a root: heap indices 1 .. storedPerRoot() - 1 (depths 0 .. leafDepth - 2).
  std::size_t storedPerRoot() const { return std::size_t(1) << (leafDepth() - 1); }
  // A vertex clamped onto the grid.
  glm::ivec2 clampToGrid(glm::ivec2 uv) const;
};

// The three vertices of a bintree node: apex, and the hypotenuse's left and right ends,
// counter-clockwise seen from above.
struct BintreeTriangle {
  glm::ivec2 apex, left, right;
};

// Root `root` (0 or 1) of block (bx, by): root 0 has its apex at the block's south-east corner,
// root 1 at its north-west corner; both have the SW-NE diagonal as hypotenuse.
BintreeTriangle rootTriangle(const BintreeDomain& domain, int bx, int by, int root);
// Children of a node (split at the hypotenuse's midpoint c): left (c, apex, left), right
// (c, right, apex).
BintreeTriangle leftChild(const BintreeTriangle& t);
BintreeTriangle rightChild(const BintreeTriangle& t);

// Height of the (clamped) sample at (u, v), metres.
float heightAt(const HeightGrid& grid, glm::ivec2 uv);
// |z(c) - (z(l) + z(r)) / 2| of a node whose hypotenuse can be split, metres.
float midpointError(const HeightGrid& grid, const BintreeTriangle& t);

// Whether a half cell's hypotenuse is the cell's SW-NE diagonal (the one drawn).
bool hasDrawnDiagonal(const BintreeTriangle& halfCell);
// |z(sw) + z(ne) - z(nw) - z(se)| / 2 of the cell whose south-west sample is `southWest`
// (clamped samples), metres: how far its two triangulations are apart at most.
float cellTwist(const HeightGrid& grid, glm::ivec2 southWest);
// The bound of a node whose children are half cells: its midpoint error plus the twist of each
// child's cell that emit() turns (see above), metres.
float lastSplitBound(const HeightGrid& grid, const BintreeTriangle& t);

// One block's bounds and height range.
struct BlockBounds {
  std::vector<std::uint16_t> bounds;  // 2 * storedPerRoot(), root-major; index 0 of each unused
  float minHeightM = 0.0f, maxHeightM = 0.0f;  // over the block's (clamped) samples
  std::array<float, 2> rootBoundM{};           // the roots' bounds, exact
};

BlockBounds computeBlockBounds(const HeightGrid& grid, const BintreeDomain& domain, int bx, int by);

// Decodes a stored bound, metres (+infinity when saturated).
float decodeBound(std::uint16_t stored);
std::uint16_t encodeBound(float metres);

}  // namespace tellus::roam
