#include "tellus/tiles/pyramid_layout.hpp"

#include <bit>

namespace tellus {
namespace {
int ceilDiv(int a, int b) {
  return (a + b - 1) / b;
}
}  // namespace

Result<PyramidLayout> PyramidLayout::create(int dataWidth, int dataHeight, int tileSize) {
  if (tileSize < 16 || tileSize > kMaxTileSize || !std::has_single_bit(unsigned(tileSize))) {
    return makeError("tile size must be a power of two from 16 to {}, got {}", kMaxTileSize,
                     tileSize);
  }
  if (dataWidth < 2 || dataHeight < 2) {
    return makeError("a pyramid needs at least 2x2 samples, got {}x{}", dataWidth, dataHeight);
  }
  PyramidLayout layout;
  layout.dataWidth_ = dataWidth;
  layout.dataHeight_ = dataHeight;
  layout.tileSize_ = tileSize;
  if (dataWidth > kMaxSide || dataHeight > kMaxSide) {
    return makeError("a pyramid holds at most {} samples per side, got {}x{}", kMaxSide, dataWidth,
                     dataHeight);
  }
  const int tiles = std::max(ceilDiv(dataWidth - 1, tileSize), ceilDiv(dataHeight - 1, tileSize));
  layout.levelCount_ = 1 + int(std::bit_width(unsigned(tiles - 1)));
  return layout;
}

int PyramidLayout::tilesX(int level) const {
  return ceilDiv(ceilDiv(dataWidth_ - 1, tileSize_), stride(level));
}
int PyramidLayout::tilesY(int level) const {
  return ceilDiv(ceilDiv(dataHeight_ - 1, tileSize_), stride(level));
}

std::size_t PyramidLayout::tileCount() const {
  std::size_t count = 0;
  for (int level = 0; level < levelCount_; ++level) {
    count += std::size_t(tilesX(level)) * std::size_t(tilesY(level));
  }
  return count;
}

bool PyramidLayout::contains(TileKey key) const {
  return key.level >= 0 && key.level < levelCount_ && key.x >= 0 && key.x < tilesX(key.level) &&
         key.y >= 0 && key.y < tilesY(key.level);
}

int PyramidLayout::dataWidthAt(int level) const {
  return ceilDiv(dataWidth_ - 1, stride(level)) + 1;
}
int PyramidLayout::dataHeightAt(int level) const {
  return ceilDiv(dataHeight_ - 1, stride(level)) + 1;
}

}  // namespace tellus
