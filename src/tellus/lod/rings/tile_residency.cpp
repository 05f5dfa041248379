#include "tellus/lod/rings/tile_residency.hpp"

#include <limits>

namespace tellus {

Result<TileResidency> TileResidency::create(const PyramidLayout& layout, int slots) {
  if (slots < 1 || slots > 2048) return makeError("GPU tile slots must be 1..2048, got {}", slots);
  if (layout.levelCount() < 1 || layout.levelCount() > 31) {
    return makeError("a pyramid of {} levels is not supported", layout.levelCount());
  }
  TileResidency r;
  r.slots_.resize(std::size_t(slots));
  int offset = 0;
  for (int level = 0; level < layout.levelCount(); ++level) {
    r.levelOffset_.push_back(offset);
    r.tilesX_.push_back(layout.tilesX(level));
    offset += layout.tilesX(level) * layout.tilesY(level);
  }
  r.pageTable_.assign(std::size_t(offset), -1);
  r.requestFrame_.assign(std::size_t(offset), 0);
  return r;
}

void TileResidency::touch(TileKey key) {
  const int slot = slotOf(key);
  if (slot >= 0) slots_[std::size_t(slot)].lastUse = frame_;
}

bool TileResidency::firstRequestThisFrame(TileKey key) {
  std::uint64_t& last = requestFrame_[pageIndex(key)];
  if (last == frame_) return false;
  last = frame_;
  return true;
}

int TileResidency::acquireSlot() {
  int best = -1;
  std::uint64_t oldest = std::numeric_limits<std::uint64_t>::max();
  for (std::size_t i = 0; i < slots_.size(); ++i) {
    const Slot& s = slots_[i];
    if (s.key.level < 0) return int(i);  // free
    if (s.pinned || s.lastUse >= frame_) continue;
    if (s.lastUse < oldest) {
      oldest = s.lastUse;
      best = int(i);
    }
  }
  if (best >= 0) {
    pageTable_[pageIndex(slots_[std::size_t(best)].key)] = -1;
    slots_[std::size_t(best)] = Slot{};
    ++evictions_;
    changed_ = true;
  }
  return best;
}

void TileResidency::assign(int slot, TileKey key, bool pinned) {
  Slot& s = slots_[std::size_t(slot)];
  if (s.key.level >= 0) pageTable_[pageIndex(s.key)] = -1;
  s.key = key;
  s.lastUse = frame_;
  s.pinned = pinned;
  pageTable_[pageIndex(key)] = slot;
  changed_ = true;
}

int TileResidency::closedLevel(int x0, int y0, int wantedLevel) const {
  int level = coarsestLevel();
  if (slotOf({level, x0 >> level, y0 >> level}) < 0) return level + 1;
  while (level > wantedLevel && slotOf({level - 1, x0 >> (level - 1), y0 >> (level - 1)}) >= 0) {
    --level;
  }
  return level;
}

int TileResidency::residentCount() const {
  int n = 0;
  for (const Slot& s : slots_) n += s.key.level >= 0 ? 1 : 0;
  return n;
}

}  // namespace tellus
