#pragma once
// RINGO (seed 002): the matrix of blocks around the viewer and its reorganisation when the
// viewer crosses the border of the central block. GL-free.
//
// The matrix is toroidal: the block of (unwrapped) tile column x and row y lives in slot
// (x mod side, y mod side), so a block that stays in the matrix keeps its slot and its GPU
// buffer ("moves by pointer" in the seed's words, here without moving at all). When the centre
// moves, a slot changes only if it now holds another block (one that entered the matrix:
// reloaded from the store) or the same block at another level: coarser, it is derived from its
// own finer samples (the seed's "D" blocks, behind the viewer); finer, it is reloaded (the
// seed's "R" blocks, in front). recentre() lists exactly those slots, each with its lane: the
// matrix column for a move north or south, the row for a move east or west (the seed's
// Figure 4: one task per lane); lanes share nothing, so they can be rebuilt in parallel.
//
// Column x is unwrapped (any integer): the tile's own column is x mod tilesX(depth), so crossing
// the antimeridian is an ordinary step. Rows beyond a pole hold no block.
#include <cstdint>
#include <vector>

#include "tellus/lod/ringo/ringo_layout.hpp"
#include "tellus/tiles/global_tiling.hpp"

namespace tellus {

struct RingoBlock {
  bool exists = false;  // false for a slot whose row lies beyond a pole
  GeoTileKey key;       // the depth-D tile it covers (x wrapped into 0 .. tilesX - 1)
  int level = 0;        // its ring's level: layout.cellsAt(level) cells a side
  bool operator==(const RingoBlock&) const = default;
};

enum class RingoBlockSource {
  Reloaded,  // read from the store (a block new to the slot, or one that became finer)
  Derived,   // the slot's own block, coarser: its previous samples taken every 2^k-th
  Removed,   // the slot's row now lies beyond a pole: it holds nothing
};

struct RingoBlockUpdate {
  int slot = 0;      // index into the matrix's slots (row-major: y mod side, x mod side)
  int lane = 0;      // the column (north/south moves) or row (east/west) of the slot, 0 .. side-1
  RingoBlock block;  // what the slot holds after the move
  RingoBlockSource source = RingoBlockSource::Reloaded;
  int previousLevel = 0;  // Derived: the level its samples come from
};

class RingoBlockMatrix {
 public:
  // The matrix at `depth` centred on tile (centreX, centreY) (centreX unwrapped).
  RingoBlockMatrix(RingoLayout layout, int depth, std::int64_t centreX, int centreY);

  const RingoLayout& layout() const { return layout_; }
  int depth() const { return depth_; }
  std::int64_t centreX() const { return centreX_; }
  int centreY() const { return centreY_; }
  int slotCount() const { return layout_.side() * layout_.side(); }
  const RingoBlock& slot(int index) const { return slots_[std::size_t(index)]; }
  // The slot of the block at offset (dx, dy) blocks from the centre (east, south positive).
  int slotAt(int dx, int dy) const;
  const RingoBlock& at(int dx, int dy) const { return slot(slotAt(dx, dy)); }

  // Moves the centre to (x, y), any distance, and returns the slots that changed (above). The
  // matrix afterwards equals one built at (x, y).
  std::vector<RingoBlockUpdate> recentre(std::int64_t x, int y);

 private:
  RingoBlock blockAt(int dx, int dy) const;  // for the current centre

  RingoLayout layout_;
  int depth_;
  std::int64_t centreX_;
  int centreY_;
  std::vector<RingoBlock> slots_;
};

}  // namespace tellus
