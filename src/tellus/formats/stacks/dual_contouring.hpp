#pragma once
// The cell rules of dual contouring as the quadrangulation pipeline uses them (seed 003,
// section 3.2.3, after Schmitz, Dietrich and Comba 2009), shared by the CPU reference and,
// written out the same way, by shaders/stacks/quad_common.glsl. GL-free.
//
// A cell is the cube between 8 density samples; corner c sits at offset (c & 1, (c >> 1) & 1,
// (c >> 2) & 1). Its classification has bit c set when corner c is inside (solid). A cell
// whose corners are neither all inside nor all outside (0 < c < 255) gets one vertex. Every
// sample-grid edge whose ends differ crosses the surface and becomes one quad joining the four
// cells around it; a cell owns the quads of the three edges leaving its corner 0 (along x, y,
// z), which is why four densities (corners 0, 1, 2, 4) decide its faces.
#include <array>
#include <cstdint>

namespace tellus::dc {

// The 12 edges of a cell as corner pairs, 4 along x, 4 along y, 4 along z.
inline constexpr std::array<std::array<int, 2>, 12> kCellEdges = {{{0, 1}, {2, 3}, {4, 5},
                                                                   {6, 7}, {0, 2}, {1, 3},
                                                                   {4, 6}, {5, 7}, {0, 4},
                                                                   {1, 5}, {2, 6}, {3, 7}}};

constexpr bool cornerInside(unsigned classification, int corner) {
  return ((classification >> corner) & 1u) != 0;
}

constexpr bool cellHasVertex(unsigned classification) {
  return classification != 0u && classification != 255u;
}

// Bit a (0 x, 1 y, 2 z): the edge from corner 0 along axis a crosses the surface.
constexpr unsigned crossingAxes(unsigned classification) {
  const bool inside0 = cornerInside(classification, 0);
  unsigned axes = 0;
  if (cornerInside(classification, 1) != inside0) axes |= 1u;
  if (cornerInside(classification, 2) != inside0) axes |= 2u;
  if (cornerInside(classification, 4) != inside0) axes |= 4u;
  return axes;
}

// The quads cell (i, j, k) of a node of n^3 cells emits: its crossing axes, less those whose
// four cells are not all in the node, and less those a neighbouring node emits. Nodes overlap
// by one cell (their last cell along an axis is the next node's first), so along axis a the
// quad of a cell in the last layer (index n - 1) is left to the next node, and along the two
// other axes the cell must not be in the first layer (the quad's other cells lie before it).
constexpr unsigned ownedQuads(unsigned classification, int i, int j, int k, int n) {
  unsigned axes = crossingAxes(classification);
  if (!(i <= n - 2 && j >= 1 && k >= 1)) axes &= ~1u;
  if (!(i >= 1 && j <= n - 2 && k >= 1)) axes &= ~2u;
  if (!(i >= 1 && j >= 1 && k <= n - 2)) axes &= ~4u;
  return axes;
}

// A cell's code in the pipeline's lookup table (CellEntry::code): its classification (bits 0-7),
// the quads it owns (bits 8-10, x y z) and whether it emits a vertex (bit 11). Without
// stitching a cell emits a vertex when its classification says so; a stitched node's border
// cells borrow the vertices of the coarser level's cells (stacks/stitched_quadrangulation.hpp).
inline constexpr unsigned kVertexBit = 1u << 11;
constexpr unsigned cellCode(unsigned classification, unsigned ownedQuads, bool hasVertex) {
  return classification | (ownedQuads << 8) | (hasVertex ? kVertexBit : 0u);
}
constexpr unsigned codeQuads(unsigned code) { return (code >> 8) & 7u; }
constexpr bool codeHasVertex(unsigned code) { return (code & kVertexBit) != 0u; }

// The four cells around the edge from cell (0, 0, 0)'s corner 0 along `axis`, as offsets from
// that cell, in counter-clockwise order seen from the axis' positive side: the quad's order
// when the surface faces +axis (corner 0 inside), reversed when it faces -axis.
inline constexpr std::array<std::array<std::array<int, 3>, 4>, 3> kQuadCells = {{
    {{{0, -1, -1}, {0, 0, -1}, {0, 0, 0}, {0, -1, 0}}},   // x: (y, z) counter-clockwise about +x
    {{{-1, 0, -1}, {-1, 0, 0}, {0, 0, 0}, {0, 0, -1}}},   // y: (z, x) counter-clockwise about +y
    {{{-1, -1, 0}, {0, -1, 0}, {0, 0, 0}, {-1, 0, 0}}},   // z: (x, y) counter-clockwise about +z
}};

}  // namespace tellus::dc
