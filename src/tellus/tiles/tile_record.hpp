#pragma once
// What the store knows about one tile without decoding it.
#include <cstdint>

#include "tellus/tiles/pyramid_layout.hpp"

namespace tellus {

struct TileStats {
  float minHeightM = 0.0f;  // lowest and highest sample of the tile, metres
  float maxHeightM = 0.0f;
  // Largest |full-resolution height - this level's surface| over the tile's ground footprint,
  // metres, where the level's surface is the bilinear interpolation of its samples. 0 on level
  // 0. It does not include the codec's error (StoreMetadata::maxErrorM), which adds to it.
  float geometricErrorM = 0.0f;
  // Global stores: the tile's samples that no source covered (stored as 0 m), so that an update
  // (build --global --update) keeps the store's total exact. 0 in flat stores and in global
  // stores written before it was recorded.
  std::uint32_t uncoveredSamples = 0;
};

struct TileRecord {
  TileKey key;
  std::uint64_t payloadOffset = 0;
  std::uint32_t payloadBytes = 0;
  std::uint64_t payloadHash = 0;
  TileStats stats;
};

}  // namespace tellus
