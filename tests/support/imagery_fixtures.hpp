#pragma once
// Small georeferenced RGB images for the imagery tests (dem/imagery_pyramid.hpp and the spiral's
// draped imagery), written as GeoTIFFs with GDAL.
#include <array>
#include <cstdint>
#include <filesystem>
#include <functional>

namespace tellus::test {

struct TestImage {
  int width = 0, height = 0;
  // North-west corner and texel size in the CRS's units (degrees for EPSG:4326, metres for
  // EPSG:3857).
  double west = 0.0, north = 0.0, texelSize = 1.0;
  int epsg = 4326;
  // The colour of texel (x, y), row 0 north; alpha 0 masks it out (written as a fourth band).
  std::function<std::array<std::uint8_t, 4>(int x, int y)> texel;
};

// Writes `image` to `path` (GeoTIFF, 4 bands, the fourth an alpha band). Fails the test on error.
void writeTestImage(const TestImage& image, const std::filesystem::path& path);

// A pattern whose every texel is distinct enough to locate: red from x, green from y, blue a
// 16-texel checkerboard.
std::array<std::uint8_t, 4> testPattern(int x, int y);

}  // namespace tellus::test
