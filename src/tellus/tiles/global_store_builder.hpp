#pragma once
// Builds a global store (global_store.hpp) from several DEM sources at once:
// `tellus build --global etopo5.tif N3?E12?.hgt n1?_w062_3arc_v2.bil -o earth.tstore`.
//
// Each source feeds tiles down to its native depth, the shallowest depth whose sample spacing
// is at most 1.1 times its own (ETOPO5's 5 arc-minutes: depth 3, 5.27', with 256-cell tiles;
// SRTM3's 3 arc-seconds: depth 10, 2.47"). A tile exists where some source reaches its depth (both roots
// always), so the pyramid is complete down to the coarse global source and sparse below it.
// Every tile is filled by GDAL's warper from all the sources that touch it, finest first
// (latlon_warper.hpp): a sample takes the finest source with data there, so SRTM voids fall
// back to ETOPO (with edgeBlendM, a source fades into the coarser ones near its edges); a
// sample no source covers is 0 m (and counted). The pole rows get one height
// each (the mean of the sources along the pole), and the eastern column at 180 degrees is
// warped at -180 so that it equals the western column of the first tile.
//
// The quadtree is split at a depth S into subtrees of about equal work (source samples read),
// dealt to the job's ranks (`mpirun -np N`; one rank without mpirun) in contiguous runs. Each
// rank walks its subtrees depth first, children in parallel (oneTBB): a tile is warped, measured
// against all its ancestors' surfaces (exact geometric errors, global_store.hpp), its subtree
// built, then it is encoded and spooled. The tiles above S are made by every rank from every
// second sample of the subtrees' roots (a point's value does not depend on the tile it is warped
// for, latlon_warper.hpp), warping only where no subtree lies. The ranks then copy their tiles
// into one file, laid out in the quadtree's post-order (global_build_plan.hpp): the store's
// bytes are the same for any number of ranks, threads and S. Memory per rank: one chain of
// ancestors per worker, the tiles above S, GDAL's capped block cache, and the index (40 bytes a
// tile). The file is written through TileStoreWriter: complete or not at all, checksummed; the
// ranks must share the output's file system.
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "tellus/core/ranks.hpp"
#include "tellus/core/result.hpp"
#include "tellus/tiles/global_store_metadata.hpp"
#include "tellus/dem/height_encoding.hpp"
#include "tellus/tiles/tile_codec.hpp"

namespace tellus {

struct GlobalBuildOptions {
  int tileCells = 256;  // cells per tile side, a power of two
  std::string codec = "zstd";
  std::optional<double> maxErrorM;  // lossy codecs: guaranteed bound (default 1 m)
  double quantumM = 0.01;           // warped heights are not whole metres: centimetres
  int zstdLevel = kDefaultZstdLevel;
  int maxDepth = 12;  // no source feeds tiles deeper than this
  // How 8-bit RGB sources encode heights; Plain refuses them. Other sources are unaffected.
  HeightEncoding rgbEncoding = HeightEncoding::Plain;
  // A source's 0 m samples (SRTM stores the sea as exactly 0 m) yield to a coarser source's sea
  // floor there (LatLonWarper::open); false keeps them.
  bool zeroYieldsToSeaFloor = true;
  // Metres over which each source that does not cover the globe fades into the coarser sources
  // after it, inside its edges (LatLonWarper's edge blending): a fine DEM inserted into a
  // global one meets it without a cliff. 0 keeps every source's values up to its edge.
  double edgeBlendM = 0.0;
  // The depth whose tiles root the subtrees dealt to ranks (chooseSplitDepth when unset). It
  // changes where the work is done, never the bytes written.
  std::optional<int> splitDepth;
  // An update (`build --global --update OLD NEW...`): `previous` is a global store built from the
  // first `newFrom` inputs, in the order its metadata lists its sources, with these options; the
  // inputs after them are new. Only the tiles the new sources reach (and the pole rows, if the
  // poles move) are warped again; the others are read back from `previous`, all are measured
  // again, and the store is byte-identical to a build of all the inputs.
  struct Update {
    std::filesystem::path previous;
    std::size_t newFrom = 0;
  };
  std::optional<Update> update;
};

struct GlobalBuildReport {
  GlobalStoreMetadata metadata;
  std::size_t tiles = 0;
  std::uint64_t payloadBytes = 0;
  std::uint64_t decodedBytes = 0;
  std::uint64_t fileBytes = 0;
  double seconds = 0.0;
  int splitDepth = 0;
  std::size_t subtrees = 0;
  int ranks = 1;
  // Per rank: seconds warping its subtrees' roots, making the coarse tiles, building its
  // subtrees, and joining (exchanges, copying its tiles into the store, the index); its peak
  // resident memory.
  struct RankFigures {
    double rootsS = 0.0, coarseS = 0.0, subtreesS = 0.0, joinS = 0.0;
    std::uint64_t peakBytes = 0;
  };
  std::vector<RankFigures> perRank;
  // Tiles warped from the sources, read back from the previous store (an update), and written
  // with other bytes or statistics than the previous store's (all of them without an update).
  // The tiles above the split are made from their children and counted in none but the last.
  std::uint64_t tilesWarped = 0, tilesReadBack = 0, tilesRewritten = 0;
  std::uint64_t indexBytes = 0;  // what rank 0 alone writes at the end, besides its own tiles
};

// The depth a source of `spacingDeg` feeds tiles down to (see above), at most maxDepth.
int nativeDepth(double spacingDeg, int tileCells, int maxDepth);

// Collective when `ranks` is given (every rank calls it with the same arguments; each returns the
// same success or failure); null: this process alone.
Result<GlobalBuildReport> buildGlobalStore(const std::vector<std::filesystem::path>& inputs,
                                           const std::filesystem::path& output,
                                           const GlobalBuildOptions& options,
                                           Ranks* ranks = nullptr);

}  // namespace tellus
