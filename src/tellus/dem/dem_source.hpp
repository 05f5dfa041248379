#pragma once
// A DEM opened for streaming: any input loadDem() accepts (one raster, a mosaic of several,
// RGB-encoded tiles), read a band of rows at a time so that inputs far larger than memory can
// be processed (the pyramid builder reads 16385x16385 grids this way).
//
// Heights come out in metres (scale, offset and feet applied), row 0 = north. Voids (nodata,
// NaN, |h| >= 1e6 m) read as NaN until fillVoids() has run; after it, reads are void-free.
// One DemSource must be used from one thread at a time.
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "tellus/core/result.hpp"
#include "tellus/dem/dem_loader.hpp"
#include "tellus/dem/height_grid.hpp"

namespace tellus {

struct DemSourceInfo {
  std::string name;  // the input file, or "mosaic of N files from 'first'"
  int width = 0;
  int height = 0;
  double spacingXM = 1.0;  // ground distance between samples, metres (see HeightGrid)
  double spacingYM = 1.0;
  GeoReference georef;
  // When every height is an exact multiple of heightStepM (integer rasters, RGB-encoded
  // tiles), heightStepM is that step in metres; 0 for floating-point rasters.
  double heightStepM = 0.0;
};

// What a scan of the heights found (DemSource::scanStatistics()).
struct DemStatistics {
  bool hasValidSamples = false;  // false: every sample read was void
  float minM = 0.0f;             // over the valid samples read, metres
  float maxM = 0.0f;
  std::uint64_t voids = 0;        // void samples among those read
  std::uint64_t samplesRead = 0;  // width * height unless rows were skipped
  int rowStep = 1;                // 1: every row was read (exact); k: every k-th row
};

class DemSource {
 public:
  static Result<std::unique_ptr<DemSource>> open(const std::vector<std::filesystem::path>& inputs,
                                                 const DemLoadOptions& options = {});
  ~DemSource();
  DemSource(const DemSource&) = delete;
  DemSource& operator=(const DemSource&) = delete;

  const DemSourceInfo& info() const;

  // Caps GDAL's block cache (process-wide; GDAL's default is 5% of RAM). Streaming readers
  // set it low so that memory stays bounded whatever the input size.
  static void setReadCacheLimit(std::size_t bytes);

  // Reads rows [firstRow, firstRow + rowCount) into `heights` (width * rowCount values).
  Status readRows(int firstRow, int rowCount, std::span<float> heights);

  // Streams the heights once in constant memory: height range and void count. Reads every row
  // while that is at most `maxSamplesRead` samples, else every k-th row (statistics of a
  // sample, marked by rowStep > 1), so that even a 100000 x 100000 raster is described in
  // seconds.
  Result<DemStatistics> scanStatistics(std::uint64_t maxSamplesRead = std::uint64_t(1) << 27);

  // Scans the whole input for voids and, if it has any, fills them by inverse-distance
  // interpolation (GDALFillNodata). When the grid has at most `inMemorySamples` samples and at
  // most a quarter of them (and 4 M) are voids, each 256-sample block holding voids is filled
  // from a window reaching 256 samples beyond it and the filled heights are kept aside and
  // applied to every later read (no copy of the input: SRTM's few voids cost milliseconds).
  // Otherwise the whole raster is filled into a private copy that later reads come from: in
  // memory when it fits `inMemorySamples`, else a temporary GeoTIFF in a private scratch folder
  // inside `scratchFolder` that also holds GDAL's work files (all removed by the destructor;
  // those of a killed process by the next fill in the same folder). Voids out of reach of any
  // data take the lowest valid height. Returns the number of void samples.
  Result<std::size_t> fillVoids(const std::filesystem::path& scratchFolder,
                                std::size_t inMemorySamples = std::size_t(1) << 27);

  // Fills voids as reads meet them, with no scan first (a streaming reader that reads every
  // sample once saves a whole pass): each 256-sample block holding voids is filled the first
  // time a read touches it, exactly as fillVoids() fills it block by block, and kept for later
  // reads. A read fails, and voidFillingOnReadGaveUp() turns true, once the voids met are more
  // than a quarter of the samples (or 4 M), or a block holds voids with no data within 256
  // samples: the caller then discards what it read and calls fillVoids(), which fills the
  // whole raster. Does nothing after fillVoids().
  void fillVoidsOnRead();
  bool voidFillingOnReadGaveUp() const;
  // Voids filled: by fillVoids(), or on read so far (all of them once every row was read).
  std::size_t filledVoidCount() const;

 private:
  struct Impl;
  explicit DemSource(std::unique_ptr<Impl> impl);
  Status fillVoidsLocally(const std::vector<std::uint64_t>& voidIndices, float lowestValid);
  std::unique_ptr<Impl> impl_;
};

}  // namespace tellus
