#pragma once
// The geometry of a tile pyramid.
//
// Level 0 holds the input at full resolution; level L keeps every 2^L-th sample of level 0
// (a subsample, so a coarse vertex is always a fine vertex and heights agree exactly). A tile
// has tileSize cells, i.e. tileSize + 1 samples, per side, and shares its border samples with
// its neighbours. Tile (x, y) of level L starts at level-L sample (x * tileSize, y * tileSize);
// y = 0 is the northern row of tiles, as row 0 of a HeightGrid is north.
//
// Level 0 has ceil((dataWidth - 1) / tileSize) x ceil((dataHeight - 1) / tileSize) tiles, each
// coarser level ceil(half) of the finer one's, down to a single tile. Samples east or south of
// the data repeat the last column / row of the data (edge clamping), so every tile is full.
#include <compare>
#include <cstddef>
#include <cstdint>
#include <functional>

#include "tellus/core/result.hpp"
#include "tellus/dem/height_grid.hpp"
#include "tellus/tiles/tile_codec.hpp"

namespace tellus {

struct TileKey {
  int level = 0;
  int x = 0;
  int y = 0;
  auto operator<=>(const TileKey&) const = default;
};

struct TileKeyHash {
  std::size_t operator()(const TileKey& k) const noexcept {
    return std::hash<std::uint64_t>{}((std::uint64_t(std::uint32_t(k.level)) << 56) ^
                                      (std::uint64_t(std::uint32_t(k.x)) << 28) ^
                                      std::uint64_t(std::uint32_t(k.y)));
  }
};

class PyramidLayout {
 public:
  // Largest tile side accepted, in cells.
  static constexpr int kMaxTileSize = 4096;
  // Largest data side accepted, in samples (height_grid.hpp).
  static constexpr int kMaxSide = kMaxGridSide;

  // tileSize must be a power of two in [16, kMaxTileSize]; the data at least 2x2 samples.
  static Result<PyramidLayout> create(int dataWidth, int dataHeight, int tileSize);

  int tileSize() const { return tileSize_; }
  int samplesPerSide() const { return tileSize_ + 1; }
  TileShape tileShape() const { return {tileSize_ + 1, tileSize_ + 1}; }
  int dataWidth() const { return dataWidth_; }
  int dataHeight() const { return dataHeight_; }
  int levelCount() const { return levelCount_; }
  int tilesX(int level) const;
  int tilesY(int level) const;
  std::size_t tileCount() const;  // over all levels
  bool contains(TileKey key) const;
  // Distance between samples of `level`, in level-0 samples (2^level).
  static int stride(int level) { return 1 << level; }
  // Samples of `level` that cover the data: ceil((dataWidth - 1) / stride) + 1.
  int dataWidthAt(int level) const;
  int dataHeightAt(int level) const;

 private:
  int dataWidth_ = 0, dataHeight_ = 0, tileSize_ = 0, levelCount_ = 0;
};

}  // namespace tellus
