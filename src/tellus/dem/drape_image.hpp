#pragma once
// A colour image draped over the globe: any RGB raster GDAL reads whose pixels are a
// latitude/longitude grid (NASA's Blue Marble: BlueMarbleAlbedo.jpg and its .jgw world file),
// loaded into memory as 8-bit RGB with where it lies. A raster without a CRS whose grid lies
// within the globe's degrees is taken as WGS 84 latitude/longitude (world files carry none).
#include <filesystem>

#include "tellus/core/result.hpp"
#include "tellus/core/rgb_image.hpp"

namespace tellus {

struct DrapeImage {
  RgbImage image;  // row 0 north
  // The image's outer edges (pixel-is-area), degrees.
  double westDeg = -180.0, eastDeg = 180.0, northDeg = 90.0, southDeg = -90.0;
};

// Errors name the file: not a raster, fewer than 3 bands (the first three are red, green,
// blue), bands that are not 8-bit, no georeferencing, a rotated grid, a projected CRS, a grid
// beyond the globe, or more than `maxSide` pixels a side (GPU texture limits).
Result<DrapeImage> loadDrapeImage(const std::filesystem::path& path, int maxSide = 16384);

}  // namespace tellus
