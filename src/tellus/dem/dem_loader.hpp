#pragma once
// Loads raster DEMs through GDAL into one HeightGrid: any raster GDAL reads (SRTM .hgt,
// GeoTIFF of any sample type and nodata value, 16-bit PNG, ...) and RGB-encoded web tiles.
// Several inputs are mosaicked into one grid (they must share a CRS); void samples (nodata,
// NaN, |h| >= 1e6 m) are filled by interpolation from their surroundings; the ground size of a
// sample is computed in metres from the CRS. Not thread-safe with respect to GDAL's
// configuration, but loads on different threads are fine.
#include <filesystem>
#include <optional>
#include <vector>

#include "tellus/core/result.hpp"
#include "tellus/dem/height_encoding.hpp"
#include "tellus/dem/height_grid.hpp"

namespace tellus {

struct DemLoadOptions {
  HeightEncoding encoding = HeightEncoding::Plain;
  // Overrides the ground distance between samples (both axes), metres. Needed for rasters
  // without georeferencing (plain PNG tiles), which otherwise get 1 m and a warning.
  std::optional<double> spacingM;
  // Bytes per sample the caller will allocate on top of the loaded grid (a renderer's GPU copy,
  // say): counted when checking, before anything is allocated, that the load fits in memory.
  double callerBytesPerSample = 0.0;
};

// Memory a loaded grid takes per sample (one float), and what void filling adds while it runs
// (GDAL's in-memory copy, mask and work rasters).
inline constexpr double kGridBytesPerSample = 4.0;
inline constexpr double kVoidFillBytesPerSample = 14.0;

// Refuses, with the figures and the way out (a tile store streams), a grid that would not fit
// in memory.
Result<HeightGrid> loadDem(const std::vector<std::filesystem::path>& inputs,
                           const DemLoadOptions& options = {});

}  // namespace tellus
