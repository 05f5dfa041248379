#pragma once
// Builds a tile store from DEM inputs (pyramid_layout.hpp for the geometry).
//
// The build streams: it reads the input one band of tileSize + 1 rows at a time, cuts and
// encodes the level-0 tiles of that band, feeds every coarser level its subsampled rows and
// emits a coarser tile row when it is complete. Memory therefore grows with the input's width,
// not its area (about 3 * (tileSize + 1) * width * 4 bytes of bands in flight plus one band per
// level), and the work runs on all cores (a oneTBB pipeline: read, encode, write).
//
// Geometric errors are exact: a level-L tile's error is the largest |h - I_L| over the
// full-resolution samples h of its footprint, I_L being the bilinear surface of its samples.
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "tellus/core/result.hpp"
#include "tellus/dem/dem_loader.hpp"
#include "tellus/tiles/store_metadata.hpp"
#include "tellus/tiles/tile_codec.hpp"

namespace tellus {

struct BuildOptions {
  int tileSize = 256;  // cells per tile side
  std::string codec = "zstd";
  // Lossy codecs (bounded, lerc): the guaranteed bound on |stored - input|, metres (default 1).
  // The fractal codec adds its residual layer to guarantee it only when given; without it the
  // store records the largest error the build measured.
  std::optional<double> maxErrorM;
  // --codec fractal's parameters. Here the thresholds are in metres (the build converts them
  // to steps of the quantum) and `residual` is ignored (set from maxErrorM).
  FractalOptions fractal;
  // Metres per stored integer step. Default: the input's own step when its heights are
  // integers (or RGB-encoded), else 0.01 m.
  std::optional<double> quantumM;
  int zstdLevel = 12;
  DemLoadOptions dem;
};

struct BuildReport {
  StoreMetadata metadata;
  std::size_t tiles = 0;
  std::uint64_t payloadBytes = 0;  // encoded tiles
  std::uint64_t decodedBytes = 0;  // the same tiles as int32 samples
  std::uint64_t fileBytes = 0;
  double seconds = 0.0;
};

Result<BuildReport> buildPyramid(const std::vector<std::filesystem::path>& inputs,
                                 const std::filesystem::path& output, const BuildOptions& options);

}  // namespace tellus
