#pragma once
// The rings structure of seed 000 (rings of patches around the viewer), GL-free.
//
// The terrain is a grid of patchesX x patchesY square patches (patch (x, y), y = 0 the northern
// row, like tiles). Around the centre patch lie concentric rings of patches; a patch's
// Chebyshev distance d = max(|dx|, |dy|) from the centre decides its level of detail:
//
//   level(d) = 0 for d <= 1 (the centre and the first ring share the finest level),
//              floor(log2(d)) beyond, capped at maxLevel,
//
// so "ring i" — the patches at level i — spans distances [2^i, 2^(i+1) - 1]: rings double in
// width as they double in distance, cell size grows with distance, and neighbouring patches
// differ by at most one level (which the GPU stitching needs). `rings` rings reach distance
// 2^rings - 1.
//
// The structure is a (2D+1)^2 array (D the reach) addressed toroidally: patch (x, y) lives in
// slot (x mod S, y mod S). updateRings(i, j) moves the centre to a neighbouring patch and
// refills only the row and/or column of slots whose patches left the window: O(S) work, not
// O(S^2). Each patch knows its orientation relative to the centre (N, NE, E, ... as seen from
// the centre), which with the level step tells which of its edges meet a coarser neighbour.
#include <array>
#include <cstdint>
#include <vector>

#include "tellus/core/result.hpp"

namespace tellus {

enum class PatchOrientation : std::uint8_t {
  Centre,
  North,
  NorthEast,
  East,
  SouthEast,
  South,
  SouthWest,
  West,
  NorthWest
};

// Edges of a patch, as bits of a stitch mask.
enum PatchEdge : std::uint8_t { kEdgeUp = 1, kEdgeRight = 2, kEdgeDown = 4, kEdgeLeft = 8 };

// The seed's look-up table: the edges of a patch that face away from the centre, by
// orientation (North: up; NorthEast: up and right; ...; Centre: none).
std::uint8_t outwardEdges(PatchOrientation orientation);

struct RingPatch {
  int x = 0, y = 0;     // patch coordinates in the terrain's patch grid
  bool inside = false;  // false when the window reaches past the terrain's edge
  int distance = 0;     // Chebyshev distance from the centre, patches
  int level = 0;        // level of detail (0 = finest)
  PatchOrientation orientation = PatchOrientation::Centre;
  // Edges that meet a coarser neighbour (outward edges when the next ring is one level
  // coarser): the edges the vertex shader must stitch.
  std::uint8_t stitchEdges = 0;
};

class RingsStructure {
 public:
  // rings >= 1; maxLevel >= 0 caps the level (the coarsest patch mesh); patch grid >= 1x1.
  static Result<RingsStructure> create(int rings, int maxLevel, int patchesX, int patchesY,
                                       int centreX, int centreY);

  int rings() const { return rings_; }
  int reach() const { return reach_; }  // D = 2^rings - 1
  int side() const { return side_; }    // S = 2D + 1 slots per side
  int centreX() const { return centreX_; }
  int centreY() const { return centreY_; }
  int maxLevel() const { return maxLevel_; }
  static int levelAtDistance(int distance, int maxLevel);

  // The viewer's height above the ground, in patch widths (>= 0; beyond the seed): patches are
  // treated as at least this far away, so that a high viewer does not draw the ground beneath
  // it at full detail. Levels still differ by at most one between neighbours. Default 0.
  void setViewerHeight(int patches) { viewerHeight_ = patches < 0 ? 0 : patches; }
  int viewerHeight() const { return viewerHeight_; }
  // Level of detail of patch (x, y) for the current centre and viewer height.
  int levelOf(int x, int y) const;

  // Moves the centre to (i, j), one of the eight neighbours of the current centre (or the
  // centre itself, a no-op), and refills the slots whose patches left the window.
  // Returns the number of slots refilled.
  Result<int> updateRings(int i, int j);

  // The patch at offset (dx, dy) from the centre, |dx|, |dy| <= reach().
  RingPatch patchAt(int dx, int dy) const;
  // The patch stored in slot (sx, sy) (toroidal storage), for tests and GPU residency.
  RingPatch slot(int sx, int sy) const;
  // Every patch of the window that lies inside the terrain.
  std::vector<RingPatch> activePatches() const;

 private:
  struct Slot {
    int x = 0, y = 0;  // the patch this slot holds
  };
  RingPatch describe(int x, int y) const;
  void fillSlot(int x, int y);
  static int wrap(int v, int n) { return ((v % n) + n) % n; }

  int rings_ = 0, maxLevel_ = 0, reach_ = 0, side_ = 0;
  int patchesX_ = 0, patchesY_ = 0;
  int centreX_ = 0, centreY_ = 0;
  int viewerHeight_ = 0;
  std::vector<Slot> slots_;
};

}  // namespace tellus
