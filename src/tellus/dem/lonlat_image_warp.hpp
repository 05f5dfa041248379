#pragma once
// An RGB image of a latitude/longitude box, warped (GDAL, bilinear) from any georeferenced
// colour raster: a Landsat scene in Web Mercator, NASA's Blue Marble JPEG with its world file,
// an aerial GeoTIFF in UTM. What `tellus export --gltf --texture` drapes on a mesh.
//
// Contract: pixel (i, j) of the result covers longitudes west + [i, i + 1) * (east - west) / width
// and latitudes north - [j, j + 1) * (north - south) / height (row 0 north, pixel-is-area).
// Where the source has no valid pixel (outside it, or masked: a scene's rotated footprint), the
// result is `fill`; along the mask's edge the source's coverage blends it with `fill`.
// A source without a CRS whose grid lies within the globe's degrees is taken as WGS 84
// latitude/longitude (world files carry none).
#include <array>
#include <cstdint>
#include <filesystem>

#include "tellus/core/result.hpp"
#include "tellus/core/rgb_image.hpp"

namespace tellus {

struct LonLatImageRequest {
  double westDeg = 0.0, southDeg = 0.0, eastDeg = 0.0, northDeg = 0.0;
  int width = 0, height = 0;  // pixels, 1 to 16384 each
  std::array<std::uint8_t, 3> fill{204, 204, 204};
};

struct LonLatImage {
  RgbImage image;
  double coveredFraction = 0.0;  // of the result's pixels that the source covers (0..1)
};

// Errors name the file: not a raster, fewer than 3 bands or bands that are not 8-bit, no
// georeferencing, a CRS PROJ cannot turn into latitude/longitude, a box or size out of range,
// a source that covers none of the box.
Result<LonLatImage> warpImageToLonLat(const std::filesystem::path& source, const LonLatImageRequest& request);

}  // namespace tellus
