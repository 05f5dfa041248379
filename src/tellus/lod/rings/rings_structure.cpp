#include "tellus/lod/rings/rings_structure.hpp"

#include <algorithm>
#include <bit>
#include <cstdlib>

namespace tellus {

std::uint8_t outwardEdges(PatchOrientation orientation) {
  switch (orientation) {
    case PatchOrientation::Centre:
      return 0;
    case PatchOrientation::North:
      return kEdgeUp;
    case PatchOrientation::NorthEast:
      return kEdgeUp | kEdgeRight;
    case PatchOrientation::East:
      return kEdgeRight;
    case PatchOrientation::SouthEast:
      return kEdgeRight | kEdgeDown;
    case PatchOrientation::South:
      return kEdgeDown;
    case PatchOrientation::SouthWest:
      return kEdgeDown | kEdgeLeft;
    case PatchOrientation::West:
      return kEdgeLeft;
    case PatchOrientation::NorthWest:
      return kEdgeLeft | kEdgeUp;
  }
  return 0;
}

int RingsStructure::levelAtDistance(int distance, int maxLevel) {
  if (distance <= 1) return 0;
  return std::min(int(std::bit_width(unsigned(distance))) - 1, maxLevel);
}

Result<RingsStructure> RingsStructure::create(int rings, int maxLevel, int patchesX, int patchesY,
                                              int centreX, int centreY) {
  if (rings < 1 || rings > 14) return makeError("rings must be 1..14, got {}", rings);
  if (maxLevel < 0) return makeError("the coarsest level must be >= 0, got {}", maxLevel);
  if (patchesX < 1 || patchesY < 1) {
    return makeError("the patch grid must be at least 1x1, got {}x{}", patchesX, patchesY);
  }
  RingsStructure s;
  s.rings_ = rings;
  s.maxLevel_ = maxLevel;
  s.reach_ = (1 << rings) - 1;
  s.side_ = 2 * s.reach_ + 1;
  s.patchesX_ = patchesX;
  s.patchesY_ = patchesY;
  s.centreX_ = centreX;
  s.centreY_ = centreY;
  s.slots_.resize(std::size_t(s.side_) * std::size_t(s.side_));
  for (int dy = -s.reach_; dy <= s.reach_; ++dy) {
    for (int dx = -s.reach_; dx <= s.reach_; ++dx) s.fillSlot(centreX + dx, centreY + dy);
  }
  return s;
}

void RingsStructure::fillSlot(int x, int y) {
  Slot& slot =
      slots_[std::size_t(wrap(y, side_)) * std::size_t(side_) + std::size_t(wrap(x, side_))];
  slot.x = x;
  slot.y = y;
}

Result<int> RingsStructure::updateRings(int i, int j) {
  const int mx = i - centreX_, my = j - centreY_;
  if (std::abs(mx) > 1 || std::abs(my) > 1) {
    return makeError("updateRings({}, {}): not a neighbour of the centre ({}, {})", i, j, centreX_,
                     centreY_);
  }
  int refilled = 0;
  centreX_ = i;
  centreY_ = j;
  // The column that entered (it reuses the slots of the column that left).
  if (mx != 0) {
    const int x = centreX_ + mx * reach_;
    for (int dy = -reach_; dy <= reach_; ++dy, ++refilled) fillSlot(x, centreY_ + dy);
  }
  // The row that entered (its corner slot is refilled twice on a diagonal move: harmless).
  if (my != 0) {
    const int y = centreY_ + my * reach_;
    for (int dx = -reach_; dx <= reach_; ++dx, ++refilled) fillSlot(centreX_ + dx, y);
  }
  return refilled;
}

RingPatch RingsStructure::describe(int x, int y) const {
  RingPatch p;
  p.x = x;
  p.y = y;
  p.inside = x >= 0 && y >= 0 && x < patchesX_ && y < patchesY_;
  const int dx = x - centreX_, dy = y - centreY_;  // dy > 0 is south
  p.distance = std::max(std::abs(dx), std::abs(dy));
  p.level = levelAtDistance(std::max(p.distance, viewerHeight_), maxLevel_);
  if (p.distance == 0) {
    p.orientation = PatchOrientation::Centre;
  } else {
    const bool north = dy == -p.distance, south = dy == p.distance;
    const bool east = dx == p.distance, west = dx == -p.distance;
    if (north && east)
      p.orientation = PatchOrientation::NorthEast;
    else if (south && east)
      p.orientation = PatchOrientation::SouthEast;
    else if (south && west)
      p.orientation = PatchOrientation::SouthWest;
    else if (north && west)
      p.orientation = PatchOrientation::NorthWest;
    else if (north)
      p.orientation = PatchOrientation::North;
    else if (south)
      p.orientation = PatchOrientation::South;
    else if (east)
      p.orientation = PatchOrientation::East;
    else
      p.orientation = PatchOrientation::West;
  }
  // Outward neighbours are at distance + 1; stitch where that is one level coarser.
  if (levelAtDistance(std::max(p.distance + 1, viewerHeight_), maxLevel_) > p.level) {
    p.stitchEdges = outwardEdges(p.orientation);
  }
  return p;
}

int RingsStructure::levelOf(int x, int y) const {
  const int distance = std::max(std::abs(x - centreX_), std::abs(y - centreY_));
  return levelAtDistance(std::max(distance, viewerHeight_), maxLevel_);
}

RingPatch RingsStructure::patchAt(int dx, int dy) const {
  const Slot& s = slots_[std::size_t(wrap(centreY_ + dy, side_)) * std::size_t(side_) +
                         std::size_t(wrap(centreX_ + dx, side_))];
  return describe(s.x, s.y);
}

RingPatch RingsStructure::slot(int sx, int sy) const {
  const Slot& s = slots_[std::size_t(sy) * std::size_t(side_) + std::size_t(sx)];
  return describe(s.x, s.y);
}

std::vector<RingPatch> RingsStructure::activePatches() const {
  // Only the part of the window that overlaps the terrain is visited.
  const int dxFirst = std::max(-reach_, -centreX_),
            dxLast = std::min(reach_, patchesX_ - 1 - centreX_);
  const int dyFirst = std::max(-reach_, -centreY_),
            dyLast = std::min(reach_, patchesY_ - 1 - centreY_);
  std::vector<RingPatch> patches;
  if (dxFirst > dxLast || dyFirst > dyLast) return patches;
  patches.reserve(std::size_t(dxLast - dxFirst + 1) * std::size_t(dyLast - dyFirst + 1));
  for (int dy = dyFirst; dy <= dyLast; ++dy) {
    for (int dx = dxFirst; dx <= dxLast; ++dx) patches.push_back(patchAt(dx, dy));
  }
  return patches;
}

}  // namespace tellus
