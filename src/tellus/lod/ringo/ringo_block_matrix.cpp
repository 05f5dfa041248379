#include "tellus/lod/ringo/ringo_block_matrix.hpp"

#include <cstdlib>

namespace tellus {
namespace {

// a mod m in 0 .. m - 1, for any sign of a.
std::int64_t wrap(std::int64_t a, std::int64_t m) {
  const std::int64_t r = a % m;
  return r < 0 ? r + m : r;
}

}  // namespace

RingoBlockMatrix::RingoBlockMatrix(RingoLayout layout, int depth, std::int64_t centreX,
                                   int centreY)
    : layout_(layout), depth_(depth), centreX_(centreX), centreY_(centreY) {
  slots_.resize(std::size_t(slotCount()));
  const int half = layout_.side() / 2;
  for (int dy = -half; dy <= half; ++dy) {
    for (int dx = -half; dx <= half; ++dx) slots_[std::size_t(slotAt(dx, dy))] = blockAt(dx, dy);
  }
}

int RingoBlockMatrix::slotAt(int dx, int dy) const {
  const int side = layout_.side();
  return int(wrap(centreY_ + dy, side)) * side + int(wrap(centreX_ + dx, side));
}

RingoBlock RingoBlockMatrix::blockAt(int dx, int dy) const {
  RingoBlock block;
  const int y = centreY_ + dy;
  if (y < 0 || y >= GlobalTiling::tilesY(depth_)) return block;  // beyond a pole
  block.exists = true;
  block.key = {depth_, int(wrap(centreX_ + dx, GlobalTiling::tilesX(depth_))), y};
  block.level = RingoLayout::levelAt(dx, dy);
  return block;
}

std::vector<RingoBlockUpdate> RingoBlockMatrix::recentre(std::int64_t x, int y) {
  const bool alongColumns = std::abs(y - centreY_) >= std::llabs(x - centreX_);
  centreX_ = x;
  centreY_ = y;
  std::vector<RingoBlockUpdate> updates;
  const int half = layout_.side() / 2;
  for (int dy = -half; dy <= half; ++dy) {
    for (int dx = -half; dx <= half; ++dx) {
      const int index = slotAt(dx, dy);
      RingoBlock& held = slots_[std::size_t(index)];
      const RingoBlock wanted = blockAt(dx, dy);
      if (wanted == held) continue;
      RingoBlockUpdate update;
      update.slot = index;
      update.lane = alongColumns ? index % layout_.side() : index / layout_.side();
      update.block = wanted;
      update.previousLevel = held.level;
      if (!wanted.exists) {
        update.source = RingoBlockSource::Removed;
      } else if (held.exists && held.key == wanted.key && held.level < wanted.level) {
        update.source = RingoBlockSource::Derived;
      } else {
        update.source = RingoBlockSource::Reloaded;
      }
      held = wanted;
      updates.push_back(update);
    }
  }
  return updates;
}

}  // namespace tellus
