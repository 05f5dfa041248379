#pragma once
// Which pyramid tiles live in which GPU texture-array slot (seed 000's cache "in video memory"),
// GL-free so that the policy can be tested without a GPU; the renderer does the uploads.
//
// - A fixed number of slots; each holds one tile, with the frame it was last used (the seed's
//   last-use timestamp). A new tile takes a free slot, else the least recently used slot that
//   is neither pinned nor used in the current frame (so a frame never evicts what it draws).
// - A page table maps every tile of the pyramid to its slot or -1: one int per tile, level by
//   level (level L's tiles from levelOffset(L), row-major). The renderer mirrors it to the GPU.
// - "Closed" residency: a patch may only draw from a level whose tiles covering it are resident
//   on that level and every coarser one. Then any two neighbouring patches can both sample the
//   coarser of their two levels along their shared edge, which keeps the mesh crack-free while
//   tiles are missing.
#include <cstdint>
#include <vector>

#include "tellus/core/result.hpp"
#include "tellus/tiles/pyramid_layout.hpp"

namespace tellus {

class TileResidency {
 public:
  // slots >= 1; the layout's pyramid must have at most 31 levels.
  static Result<TileResidency> create(const PyramidLayout& layout, int slots);

  int slotCount() const { return int(slots_.size()); }
  int levelCount() const { return int(levelOffset_.size()); }
  int coarsestLevel() const { return levelCount() - 1; }

  // Starts a new frame: slots touched from now on count as used by it.
  void beginFrame() { ++frame_; }
  std::uint64_t frame() const { return frame_; }

  // Slot of a resident tile, or -1.
  int slotOf(TileKey key) const { return pageTable_[pageIndex(key)]; }
  // Marks the tile's slot as used by this frame (no-op when not resident).
  void touch(TileKey key);
  // True the first time a tile is asked for in this frame (for de-duplicating requests).
  bool firstRequestThisFrame(TileKey key);

  // A slot for a new tile: a free one, else the least recently used slot neither pinned nor used
  // in this frame (its tile is evicted: unmapped from the page table). -1 when none is left.
  int acquireSlot();
  // Maps `key` to `slot` (from acquireSlot) and marks it used in this frame.
  void assign(int slot, TileKey key, bool pinned = false);
  // The tile in a slot (level -1 when free).
  TileKey tileIn(int slot) const { return slots_[std::size_t(slot)].key; }

  // The finest level L >= wantedLevel at which the tiles covering level-0 tile (x0, y0) are
  // resident on L and on every coarser level; coarsestLevel() + 1 when even the coarsest tile
  // is missing.
  int closedLevel(int x0, int y0, int wantedLevel) const;

  // The page table (see above), its per-level offsets and widths (tiles per row).
  const std::vector<std::int32_t>& pageTable() const { return pageTable_; }
  int levelOffset(int level) const { return levelOffset_[std::size_t(level)]; }
  int tilesX(int level) const { return tilesX_[std::size_t(level)]; }
  // True when the page table changed since the last clearChanged().
  bool changed() const { return changed_; }
  void clearChanged() { changed_ = false; }

  std::uint64_t evictions() const { return evictions_; }
  int residentCount() const;

 private:
  struct Slot {
    TileKey key{-1, 0, 0};
    std::uint64_t lastUse = 0;
    bool pinned = false;
  };
  std::size_t pageIndex(TileKey key) const {
    return std::size_t(levelOffset_[std::size_t(key.level)]) +
           std::size_t(key.y) * std::size_t(tilesX_[std::size_t(key.level)]) + std::size_t(key.x);
  }

  std::vector<Slot> slots_;
  std::vector<std::int32_t> pageTable_;
  std::vector<std::uint64_t> requestFrame_;  // per tile, the last frame it was requested in
  std::vector<int> levelOffset_, tilesX_;
  std::uint64_t frame_ = 1;
  std::uint64_t evictions_ = 0;
  bool changed_ = true;
};

}  // namespace tellus
