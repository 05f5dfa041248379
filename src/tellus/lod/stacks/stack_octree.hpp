#pragma once
// The octree of a stack terrain (seed 003, section 3.3) and its node selection. GL-free.
//
// Octree level k is level k of the stack MipMap (StackLevels). Node (k, x, y, z) holds n^3 of
// level k's density cells from sample (x, y, z) * (n - 1): neighbouring nodes overlap by one
// cell, and the children of node (k, x, y, z) are the nodes (k - 1, 2x + {0, 1}, ...), whose
// cells are the halves of their parent's. Keys start at -1 (the margin of air around the
// terrain: its walls and floor lie in the first nodes' cells), and the top level is a forest
// of a few nodes across.
//
// Selection (section 3.3): a node is split while the screen-space extent of one of its cells,
// eps = delta * w / (2 d tan(phi / 2)), exceeds tau pixels (delta: the cell's size, metres;
// d: the distance from the camera to the node's bounds; w: the viewport height in pixels,
// phi: the vertical field of view), then the selection is balanced so that nodes sharing a
// cell differ by at most one level (the stitching's precondition, section 3.4). The seed's
// "cell screen space size of 10 px" is tau = 10 on the cell's size.
//
// Beyond the seed, a node is also split while its geometric error (StackLevel::errorM: how far
// its level's surfaces lie from the finest ones, where that error lies within the node's
// heights) exceeds tau on screen: thin cave roofs, pillars and narrow passages, which vanish
// or close at coarse levels whatever their cells' size, stay until they are small on screen.
#include <algorithm>
#include <cstdint>
#include <unordered_map>
#include <vector>

#include "tellus/core/aabb.hpp"
#include "tellus/core/camera.hpp"
#include "tellus/lod/stacks/stack_levels.hpp"

namespace tellus {

struct OctreeKey {
  int level = 0;
  int x = 0, y = 0, z = 0;
  bool operator==(const OctreeKey&) const = default;
  OctreeKey parent() const { return {level + 1, x >> 1, y >> 1, z >> 1}; }  // floor halving
  OctreeKey child(int i) const {
    return {level - 1, 2 * x + (i & 1), 2 * y + ((i >> 1) & 1), 2 * z + ((i >> 2) & 1)};
  }
  // Unique for levels < 16 and keys in [-2^15, 2^15).
  std::uint64_t packed() const;
};

// Bit (dx + 1) + 3 (dy + 1) + 9 (dz + 1) of a stitch mask: the parent's neighbour at offset
// (dx, dy, dz), d in {-1, 0, 1}, is a selected (coarser) node.
constexpr int neighbourBit(int dx, int dy, int dz) { return (dx + 1) + 3 * (dy + 1) + 9 * (dz + 1); }

class StackOctree {
 public:
  explicit StackOctree(const StackLevels& levels);

  const StackLevels& levels() const { return *levels_; }
  int topLevel() const { return topLevel_; }
  int nodeCells() const { return n_; }
  // Keys of level k along each axis: [-1, nodesEnd(k)).
  std::array<int, 3> nodesEnd(int level) const;
  // The node's first sample (cell (0, 0, 0)), in level samples.
  std::array<int, 3> origin(const OctreeKey& key) const;
  // The world box of the node's cells and one cell beyond on the high sides (where a stitched
  // node's last vertices may lie), x east, y north, z up, metres.
  Aabb cellBox(const OctreeKey& key) const;
  // The node's box clipped in z to where a surface can be in it or below it (the height ranges
  // of the columns it covers, with the smoothing's reach); empty (min > max) when no level has a
  // surface in it, so neither it nor its descendants need a mesh. Tight in z: a node over a
  // cave holds only the heights between the cave's floor and the terrain's top.
  Aabb surfaceBox(const OctreeKey& key) const;
  // A cell's size (metres): the larger of the stack spacing and the cell height at its level.
  double cellSizeM(int level) const;
  // The node's geometric error (metres): the largest StackLevel::errorM of the columns it
  // reads whose error lies within `box`'s heights (its surfaceBox), 0 at level 0.
  double geometricErrorM(const OctreeKey& key, const Aabb& box) const;

 private:
  const StackLevels* levels_;
  int n_ = 17;
  int topLevel_ = 0;
};

struct SelectionView {
  glm::dvec3 camera{0.0};  // world metres
  double fovYDeg = 45.0;
  int viewportHeightPx = 1080;
  double tauPx = 10.0;  // split while a cell's screen-space extent exceeds this
  double errorTauPx = 0.0;  // and while the geometric error on screen exceeds this (0: never)
  // The screen-space extent of a cell of `sizeM` metres at `distanceM` (eps above).
  double extentPx(double sizeM, double distanceM) const;
  // Whether a node of level > 0 with these extents is split.
  bool wantsSplit(const struct SelectedNode& node) const;
};

struct SelectedNode {
  OctreeKey key;
  std::uint32_t stitchMask = 0;  // neighbourBit()s of the parent's neighbours selected
  double extentPx = 0.0;         // eps of the node's cells at the node's distance
  double errorPx = 0.0;          // its geometric error on screen at that distance
  double errorM = 0.0;           // its geometric error, metres (0 when the threshold is off)
  // How much the node needs refining (the larger of the two, for priorities).
  double needPx() const { return std::max(extentPx, errorPx); }
  Aabb box;                      // surfaceBox
};

struct StackSelection {
  std::vector<SelectedNode> nodes;  // leaves with a possible surface, finest first
  std::size_t splits = 0;           // nodes split by the eps test
  std::size_t balanceSplits = 0;    // nodes split to keep neighbours within one level
  int finestLevel = 0, coarsestLevel = 0;
};

// The leaves of the octree for `view` (no culling: the LOD of a node does not depend on where
// the camera looks, so turning the camera never changes a mesh), balanced, each with its
// stitch mask. Deterministic.
StackSelection selectStackNodes(const StackOctree& octree, const SelectionView& view);

}  // namespace tellus
