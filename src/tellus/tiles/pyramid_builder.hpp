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
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "tellus/core/result.hpp"
#include "tellus/dem/dem_loader.hpp"
#include "tellus/tiles/store_metadata.hpp"
#include "tellus/tiles/tile_codec.hpp"

namespace tellus {

// Shared by the flat and the global builders.
// --max-error of the lossy codecs when none is given, metres.
inline constexpr double kDefaultLossyMaxErrorM = 1.0;
// GDAL's block cache while building: enough for two rows of 256x256 blocks of a 64k-wide
// float raster, far below GDAL's default of 5% of RAM.
inline constexpr std::size_t kBuildReadCacheBytes = std::size_t(96) << 20;

// A lossy codec's bound on heights already rounded to `quantumM` (costing up to `roundingM`):
// whole steps of the quantum, and the store's guaranteed error (steps * quantum + rounding).
struct LossyErrorBudget {
  std::uint32_t steps = 0;
  double maxErrorM = 0.0;
};
// Errors: a bound that is not a non-negative number, below the rounding, or absurdly large.
Result<LossyErrorBudget> lossyErrorBudget(double maxErrorM, double quantumM, double roundingM);

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
  int zstdLevel = kDefaultZstdLevel;
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
