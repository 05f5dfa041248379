#pragma once
// The quadrangulation of one octree node stitched to its coarser neighbours (seed 003, section
// 3.4), CPU reference of the GPU pipeline's stitching (render/stacks/). GL-free.
//
// Same level: nodes overlap by one cell and their densities are computed with the smoothing's
// reach beyond their cells, so a shared border vertex is computed from the same numbers by
// both (the plain pipeline, quadrangulation.hpp). Different levels (at most one apart, see
// stack_octree.hpp): a fine node's cells that lie in a selected coarser node ("coarse cells")
//   - topology fitting: every density sample at a corner of a coarse cell is replaced by the
//     coarser level's sample at half its (global) index, rounded down (point sampling), so the
//     surface crosses the border where the coarser node's surface does;
//   - T-junction removal: a coarse cell's vertex is the coarser level's vertex of the coarse
//     cell it lies in, computed as the coarser node computes it; the two fine cells of a coarse
//     cell share it (their lookups are rounded to the even one), which makes some faces
//     degenerate, as the seed allows.
// The fine node's border then meets the coarser node vertex for vertex: no crack. Needs an odd
// node size of at least 9 cells, so that stitched regions of different neighbours stay clear of
// each other's smoothing (StackLevels::build checks it).
#include <array>
#include <cstdint>
#include <vector>

#include "tellus/lod/stacks/stack_octree.hpp"
#include "tellus/formats/stacks/quadrangulation.hpp"

namespace tellus {

// Which of a node's cells and samples are coarse, from its stitch mask.
struct StitchGeometry {
  int n = 17;
  // The parent's first cell in the node's cells: 2 * parent origin - node origin (0 or -(n - 1)).
  std::array<int, 3> parentFirst{};
  std::uint32_t mask = 0;

  static StitchGeometry of(const StackOctree& octree, const OctreeKey& key, std::uint32_t mask);
  // Node-local cell (may lie outside the node, -2 .. n + 1) inside a coarser selected node.
  bool coarseCell(int x, int y, int z) const;
  // Node-local sample at a corner of a coarse cell.
  bool coarseSample(int x, int y, int z) const;
};

struct StitchStats {
  std::size_t coarseSamples = 0;   // density samples replaced
  std::size_t sharedVertices = 0;  // vertices taken from the coarser level
  // Indices of the node's quads referring to a coarse cell without a coarse vertex: must be 0
  // (the stitching's invariant; tests check it).
  std::size_t faults = 0;
};

// Geomorphing (beyond the seed, which lists it as future work): every vertex of a level-k
// node has a target on the next coarser level's surface, so the renderer can slide a node's
// mesh from how its parent looked to its own shape (after a split) or back (before a merge):
//   - the vertex of the coarser level's cell that holds the vertex's cell (cell (i, j, k) lies
//     in coarse cell (i / 2, j / 2, k / 2): node origins are even), computed as the coarser
//     node computes it (at full detail the fine cells of one coarse cell collapse onto its
//     vertex, and the fine mesh takes the coarse mesh's shape);
//   - where that coarse cell has no vertex (the coarse surface passes a neighbouring cell),
//     the nearest vertex of its 26 neighbours (first in z, y, x order on a tie);
//   - none there, the top level, or a stitched coarse cell (already the coarser vertex): the
//     vertex itself.
// Neighbouring nodes of one level compute a shared vertex's target from the same numbers, so it
// is identical in both. Eight words:
//   [0..2] the target's position (world metres);
//   [3]    the vertex's border bits: bit 2a is set when its cell is the node's first along
//          axis a (x, y, z), bit 2a + 1 when it is the last (the cells that neighbouring nodes
//          share), so the renderer can pin a border that a neighbour does not morph; and from
//          bit 6 the vertex's node-local cell, 6 bits an axis (the seam blend's weight); an
//          integer below 2^24, exact in the float (seam_blend.hpp packs and reads it);
//   [4..6] the target's normal and [7] its material weights (four unorm8, the float's bits:
//          seam_blend.hpp's packMaterials), so shading blends with the position: the coarse
//          vertex's where the target is the vertex of the coarse cell that holds the vertex,
//          the vertex's own otherwise (a neighbour's vertex may lie where the coarse volume
//          has no samples for its gradient).
using MorphTarget = std::array<float, 8>;

// The node's mesh, appended to `mesh` (like quadrangulateNode). `cells` receives its lookup
// table when not null; `morphTargets`, when not null, is resized like mesh.vertices and
// receives the node's vertices' targets at their indices. With mask 0 this is
// quadrangulateNode at the node's level. seamBandCells > 0 (a stitched node): the seam blend
// (seam_blend.hpp) baked into the vertices, at most seamBandLimit() cells.
void quadrangulateStitchedNode(const StackOctree& octree, const OctreeKey& key,
                               std::uint32_t mask, StackMesh& mesh,
                               std::vector<CellEntry>* cells = nullptr,
                               StitchStats* stats = nullptr,
                               std::vector<MorphTarget>* morphTargets = nullptr,
                               int seamBandCells = 0);

// The parameters of the coarser level's volume a stitched node reads: (n - 1) / 2 + 1 cells
// from half the node's origin, whose smoothed samples cover every coarse sample the node
// point-samples and every coarse vertex it shares.
QuadParams coarseVolumeParams(const QuadParams& params);

}  // namespace tellus
