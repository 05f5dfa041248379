#pragma once
// Measures a tile codec on a whole grid the way the pyramid builder uses it: the grid is cut
// into level-0 tiles of (tileSize + 1)^2 samples, quantised, then every tile is encoded and
// decoded on one thread. Used by `tellus bench codecs` and the micro-benchmarks.
#include <cstdint>
#include <vector>

#include "tellus/core/result.hpp"
#include "tellus/dem/height_grid.hpp"
#include "tellus/tiles/tile_codec.hpp"

namespace tellus {

struct QuantisedTiles {
  TileShape shape;
  int tilesX = 0, tilesY = 0;
  std::vector<std::vector<std::int32_t>> tiles;  // row-major by tile, tilesX * tilesY
};

// Cuts `grid` into tiles (edges clamped as in the pyramid) in units of quantumM.
QuantisedTiles cutTiles(const HeightGrid& grid, int tileSize, double quantumM);

struct CodecMeasurement {
  std::uint64_t bytes = 0;             // all encoded tiles
  double encodeSeconds = 0.0;          // median over repeats, all tiles, one thread
  double encodeSecondsAllCores = 0.0;  // the same, tiles spread over every core (oneTBB)
  double decodeSeconds = 0.0;
  double maxAbsErrorM = 0.0;  // over the grid's samples, against the grid
  double rmseM = 0.0;
  std::vector<std::vector<std::byte>> payloads;  // every tile's encoding, in tile order
};

Result<CodecMeasurement> measureCodec(const TileCodec& codec, const QuantisedTiles& tiles,
                                      const HeightGrid& grid, double quantumM, int repeats);

// The grid's heights (metres) reassembled from decoded tiles (quantum steps) cut by cutTiles.
std::vector<float> assembleTiles(const std::vector<std::vector<std::int32_t>>& decoded,
                                 const QuantisedTiles& tiles, const HeightGrid& grid,
                                 double quantumM);

// max |a - b| and RMSE over two equally sized height arrays.
void compareHeights(const std::vector<float>& a, const std::vector<float>& b, double& maxAbs,
                    double& rmse);

}  // namespace tellus
