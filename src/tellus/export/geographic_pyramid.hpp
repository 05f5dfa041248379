#pragma once
// The tile pyramid that Cesium's geographic tiling scheme lays over a store, shared by the
// quantized-mesh tile set (quantized_mesh_tiler.hpp) and the 3D Tiles set (tiles3d_export.hpp):
// 2 x 1 tiles at level 0 (west and east hemispheres), each level splitting every tile in four,
// x from the antimeridian eastwards, y from the south pole northwards.
//
// Which tiles: every tile of levels 0..globeLevels (the whole globe, so that a client draws the
// planet round from any distance), then the tiles that touch the data's box. How deep: to the
// first level whose lattice of `tileSamples` a side is as fine as the store's samples, or a
// given level (at most two beyond that one). What each tile of level L may miss by, in 3-D:
// Cesium's geometric error of level L (cesiumGeometricErrorM), of which the mesh uses
// kTileBoundShare and the rest covers quantization and the chord's sag between points.
#include <array>
#include <atomic>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "tellus/core/result.hpp"
#include "tellus/export/lonlat_sampler.hpp"
#include "tellus/export/quantized_mesh_tile_builder.hpp"

namespace tellus {

// Cesium's geometric error of level `level` of the geographic scheme, metres:
// a * 2 pi * 0.25 / (65 * 2) / 2^level (CesiumTerrainProvider's estimate for a 65-sample
// heightmap; a: WGS84's semi-major axis), 77 km at level 0 and 18.8 m at level 12.
double cesiumGeometricErrorM(int level);

// The share of a level's geometric error a tile's mesh is built within.
inline constexpr double kTileBoundShare = 0.9;

// How many levels beyond the first whose lattice is as fine as the store's samples a pyramid
// may go.
inline constexpr int kExtraPyramidLevels = 2;

// Tiles x0..x1, y0..y1 (inclusive) of one level.
struct GeographicTileRange {
  int x0 = 0, y0 = 0, x1 = -1, y1 = -1;
  std::uint64_t count() const { return std::uint64_t(x1 - x0 + 1) * std::uint64_t(y1 - y0 + 1); }
  bool contains(int x, int y) const { return x >= x0 && x <= x1 && y >= y0 && y <= y1; }
};

struct GeographicPyramidOptions {
  int maxLevel = -1;     // -1: as fine as the store's samples need
  int tileSamples = 65;  // lattice samples per tile side (3..1025)
  int globeLevels = 5;   // 0..8
};

// Tiles that no finer tile replaces before the finest level (the globe's tiles beyond the
// data, at level globeLevels) are built this many levels tighter than their own level's error:
// a client draws them however close it comes, and from 3 km up the horizon is 196 km away,
// where level 5's 2.2 km chord sag would show as 10 pixels and level 8's 270 m shows as 1.2.
inline constexpr int kLeafRefinementLevels = 3;

struct GeographicPyramid {
  LonLatBox dataBox;
  int maxLevel = 0;
  int naturalMaxLevel = 0;  // the first level as fine as the samples
  std::vector<GeographicTileRange> ranges;  // one a level, 0..maxLevel
  std::uint64_t tiles = 0;

  // Whether tile (level, x, y) has no child in the pyramid.
  bool isLeaf(int level, int x, int y) const;
  // The 3-D bound its mesh is built within, metres: kTileBoundShare of its level's geometric
  // error, or of the error kLeafRefinementLevels deeper for a leaf above the finest level.
  double tileBoundM(int level, int x, int y) const;
  // The bounds of its west, east, south and north edges: the smaller of its own and its
  // neighbour's across the edge (x wraps at the antimeridian), so that both simplify the
  // shared edge alike.
  std::array<double, 4> edgeBoundsM(int level, int x, int y) const;
};

// The pyramid over `source` (the store's finest level). Errors name `storeName` and the option
// out of range (a --max-level finer than the data, --globe-levels over 8, ...).
Result<GeographicPyramid> planGeographicPyramid(const LonLatSampler& source, const std::string& storeName,
                                                const GeographicPyramidOptions& options);

// What a pyramid's level came to.
struct PyramidLevelReport {
  int level = 0;
  std::uint64_t tiles = 0;
  std::uint64_t bytes = 0;
  std::uint64_t triangles = 0;
  std::uint64_t truthSamples = 0;  // source samples (and lattice points without data) measured
  int truthStride = 1;             // 1: every source sample; k: every k-th column and row
  double geometricErrorM = 0.0;    // Cesium's, the bound
  double maxErrorM = 0.0;          // the largest 3-D miss measured over its tiles
};

// One tile's share of its level's report.
struct PyramidTileResult {
  std::uint64_t bytes = 0;
  QuantizedMeshTileStats stats;
};
// The report of `level` from its tiles' results.
PyramidLevelReport summarizeLevel(int level, const std::vector<PyramidTileResult>& tiles);

// Refuses, with the figures, a set of `files` files that cannot fit the free space (a block a
// file) or free inodes of the file system that will hold `folder`. `what` names the set.
Status checkFilesFit(const std::filesystem::path& folder, std::uint64_t files, const std::string& what,
                     const std::string& advice);

// Calls `build(x, y)` for every tile of `level`, on the worker threads (oneTBB), stopping at the
// first error, which it returns; `done` counts the tiles finished (for progress).
Status forEachPyramidTile(const GeographicPyramid& pyramid, int level,
                          const std::function<Status(int x, int y)>& build,
                          const std::function<void()>& done);

}  // namespace tellus
