#pragma once
// `tellus export STORE --3d-tiles DIR`: the terrain as a 3D Tiles 1.1 tile set of glTF tiles
// on implicit quadtrees, loadable by CesiumJS (Cesium3DTileset) and any 3D Tiles 1.1 client:
//
//   DIR/tileset.json                      an explicit root (the globe, no content) over two
//                                         implicit roots: the west (0) and east (1) hemispheres
//   DIR/H/subtrees/L/X/Y.subtree          availability (implicit_subtree.hpp), every 7 levels
//   DIR/H/tiles/L/X/Y.glb                 the tile's mesh (glb_writer.hpp)
//
// The tiles are those of Cesium's geographic scheme (geographic_pyramid.hpp): level L of
// hemisphere H holds the quantized-mesh tiles (L, H * 2^L + X, Y), X eastwards and Y
// northwards as the implicit tiling of a region wants, each built by the same construction
// (quantized_mesh_tile_builder.hpp) within 0.9 of its level's geometric error in 3-D over
// every source sample, with its exact heights. geometricError: 77 km at the implicit roots
// (Cesium's level-0 error), halved each level by implicit tiling, so every tile's content
// holds its geometric error; the explicit root's is the Earth's diameter (an empty root
// misses the planet), so that clients always refine it.
//
// Contents: TEXCOORD_0, the tile's own coordinates (s west to east, t north to south over its
// extent, so that an image of the tile, north up, drapes on it); positions in metres relative
// to the tile's centre, which is the node's translation
// (ECEF, in glTF's y-up axes: (x, z, -y), as 3D Tiles turns glTF's y-up into z-up); the data's
// normals; grey, rough material. Bounding volumes: the regions implicit tiling derives by
// halving, with one height range for all (the lowest vertex less its level's error, to the
// highest vertex), as the specification requires for quadtrees.
// Written into a temporary folder swapped into place at the end (folder_output.hpp), like the
// quantized-mesh set.
#include <filesystem>
#include <functional>
#include <vector>

#include "tellus/core/folder_output.hpp"
#include "tellus/core/result.hpp"
#include "tellus/dem/geoid.hpp"
#include "tellus/export/geographic_pyramid.hpp"
#include "tellus/export/lonlat_sampler.hpp"
#include "tellus/tiles/tile_store.hpp"

namespace tellus {

struct Tiles3dExportOptions {
  GeographicPyramidOptions pyramid;  // levels, lattice, globe levels
  const Geoid* geoid = nullptr;      // orthometric -> ellipsoidal heights when set
  const LonLatSampler* background = nullptr;  // the ground beyond the data (as for quantized mesh)
  // Contents with KHR_mesh_quantization (glb_writer.hpp): half the bytes; a vertex moves by
  // up to 0.4 % of its level's error, and neighbours' shared edges no longer meet to the bit
  // (their skirts close the gap).
  bool quantize = false;
  // Called after each tile with (tiles written, tiles in all), from worker threads.
  std::function<void(std::uint64_t, std::uint64_t)> progress;
};

struct Tiles3dExportReport {
  std::vector<PyramidLevelReport> levels;
  std::uint64_t tiles = 0;
  std::uint64_t bytes = 0;     // of the glTF contents
  std::uint64_t subtrees = 0;
  int subtreeLevels = 0;
  double minHeightM = 0.0, maxHeightM = 0.0;  // of the regions
};

// What a 3D Tiles folder holds (the marker, tileset.json, H/tiles/..., H/subtrees/...).
FolderOutputKind tiles3dFolderKind();

// Errors: a store without georeferencing, a folder that may not be replaced, a set that cannot
// fit the disk, option values out of range, unreadable tiles, write failures.
Result<Tiles3dExportReport> exportTiles3d(const TileStore& store, const std::filesystem::path& folder,
                                          const Tiles3dExportOptions& options);

}  // namespace tellus
