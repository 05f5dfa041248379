#pragma once
// A Cesium terrain tile set (quantized-mesh-1.0, geographic tiling scheme: 2 x 1 tiles at
// level 0, each level splitting every tile in four; y counted from the south, "tms") from a
// tile store, as `tellus export --quantized-mesh DIR` writes it:
//
//   DIR/layer.json          the tile set's description (levels, "available" tile ranges: the
//                           whole globe for levels 0..globeLevels, then the tiles touching the
//                           data; the octvertexnormals extension, watermask and metadata
//                           when asked for)
//   DIR/Z/X/Y.terrain       one tile (quantized_mesh_tile_builder.hpp): its vertices the
//                           store's finest samples and simplified edges, so that the surface
//                           Cesium draws is within the level's geometric error in 3-D over
//                           every sample (Earth's curvature included), with the data's normals.
//
// Cesium assumes the geometric error of level Z to be
//   a * 2 pi * 0.25 / (65 * 2) / 2^Z  metres (a: WGS84's semi-major axis)
// (CesiumTerrainProvider: getEstimatedLevelZeroGeometricErrorForAHeightmap), 77 km at level 0
// and 18.8 m at level 12; every tile's measured error is at most that of its level.
// Levels run from 0 to the first whose 65-sample lattice is as fine as the store's samples.
// Heights are the store's (above the geoid for SRTM) plus, when a geoid is given, its
// undulation (Cesium wants heights above the ellipsoid). Written into a temporary folder
// beside DIR and swapped into place at the end (tellus/core/folder_output.hpp): never a
// half-written tile set, and an existing DIR is replaced only when it is a tile set Tellus
// wrote (the marker DIR/.tellus-tileset, nothing else in it) holding no input.
#include <filesystem>
#include <functional>
#include <vector>

#include "tellus/core/folder_output.hpp"
#include "tellus/core/result.hpp"
#include "tellus/dem/geoid.hpp"
#include "tellus/dem/water_mask.hpp"
#include "tellus/export/geographic_pyramid.hpp"
#include "tellus/tiles/tile_store.hpp"

namespace tellus {

// How many levels beyond the first whose lattice is as fine as the store's samples
// QuantizedMeshExportOptions::maxLevel may ask for.
inline constexpr int kExtraQuantizedMeshLevels = kExtraPyramidLevels;

struct QuantizedMeshExportOptions {
  int maxLevel = -1;                // -1: as fine as the store's samples need
  int tileSamples = 65;             // lattice samples per tile side where there is no data
  // Levels 0..globeLevels cover the whole globe (the ellipsoid or the geoid where there is no
  // data), so that Cesium draws the planet's curvature from tiles of at most that level's
  // error; deeper levels cover the data's box only. At most 8.
  int globeLevels = 5;
  const Geoid* geoid = nullptr;     // orthometric -> ellipsoidal heights when set
  // The ground beyond the store's data (a global relief such as ETOPO5, heights above the
  // geoid; sea floors as the sea surface); unset: the geoid there, so the data's edge is a cliff.
  const LonLatSampler* background = nullptr;
  const WaterMask* waterMask = nullptr;  // the watermask extension when set
  // The metadata extension (0: none): tiles of levels 0, N, 2N... list, in their metadata, the
  // available tiles under them at the next N levels, and layer.json says metadataAvailability
  // N, as Cesium World Terrain does (N = 10 there). Cesium then learns availability from the
  // tiles as it loads them (it ignores layer.json's "available" list, still written for other
  // clients). 1 to 20.
  int metadataLevels = 0;
  // Called after each tile with (tiles written, tiles in all), from worker threads.
  std::function<void(std::uint64_t, std::uint64_t)> progress;
};

using QuantizedMeshLevelReport = PyramidLevelReport;

struct QuantizedMeshExportReport {
  std::vector<QuantizedMeshLevelReport> levels;
  std::uint64_t tiles = 0;
  std::uint64_t bytes = 0;
};

// What a quantized-mesh tile set folder holds (the marker, layer.json, Z/X/Y.terrain).
FolderOutputKind quantizedMeshFolderKind();

// Errors: a store without georeferencing, a folder that may not be replaced (above), a tile
// set that cannot fit the disk (its tile count against the free space and inodes), option
// values out of range, unreadable tiles, write failures.
Result<QuantizedMeshExportReport> exportQuantizedMesh(const TileStore& store,
                                                      const std::filesystem::path& folder,
                                                      const QuantizedMeshExportOptions& options);

}  // namespace tellus
