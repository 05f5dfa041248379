#pragma once
// An 8-bit raster whose pixels are a latitude/longitude grid (a drape, a water mask: NASA's Blue
// Marble JPEGs with their .jgw world files), opened and checked before its pixels are read. A
// raster without a CRS whose grid lies within the globe's degrees is taken as WGS 84
// latitude/longitude (world files carry none). Only dem/ includes GDAL: the dataset stays
// behind this header's functions.
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "tellus/core/result.hpp"

namespace tellus {

struct LatLonRasterBounds {
  int width = 0, height = 0;  // pixels
  int bandCount = 0;          // the raster's (the first `bands` are read)
  // The outer edges (pixel-is-area), degrees.
  double westDeg = -180.0, eastDeg = 180.0, northDeg = 90.0, southDeg = -90.0;
};

// Reads the first `bands` bands (8-bit each) of the raster at `path`, pixel-interleaved, row 0
// north. `role` names the raster in errors ("drape", "water mask"), `expected` says what it
// should have been. Errors name the file: not a raster, too few bands, bands that are not
// 8-bit, no georeferencing, a rotated grid, a projected CRS, a grid beyond the globe, or more
// than `maxSide` pixels a side.
Result<std::vector<std::uint8_t>> readLatLonRaster(const std::filesystem::path& path,
                                                   const std::string& role,
                                                   const std::string& expected, int bands,
                                                   int maxSide, LatLonRasterBounds& bounds);

}  // namespace tellus
