#include "tellus/dem/water_mask.hpp"

#include <cmath>

namespace tellus {

Result<WaterMask> WaterMask::load(const std::filesystem::path& path) {
  WaterMask mask;
  Result<std::vector<std::uint8_t>> values = readLatLonRaster(
      path, "water mask",
      "a georeferenced 8-bit raster, 0 on land and 255 on water (a GeoTIFF, or a JPEG or PNG with a "
      "world file, as BlueMarbleWater.jpg)",
      1, 65536, mask.bounds_);
  if (!values) return values.error();
  if (mask.bounds_.bandCount != 1) {
    return makeError("water mask '{}' has {} bands: a water mask is one band, 0 on land and 255 on "
                     "water (a colour image is no mask)",
                     path.string(), mask.bounds_.bandCount);
  }
  mask.values_ = std::move(values.value());
  mask.wraps_ = std::abs(mask.bounds_.eastDeg - mask.bounds_.westDeg - 360.0) < 1e-6;
  return mask;
}

std::uint8_t WaterMask::at(double lonDeg, double latDeg) const {
  const LatLonRasterBounds& b = bounds_;
  double x = (lonDeg - b.westDeg) / (b.eastDeg - b.westDeg) * b.width;
  const double y = (b.northDeg - latDeg) / (b.northDeg - b.southDeg) * b.height;
  if (wraps_) x -= std::floor(x / b.width) * b.width;
  if (!(x >= 0.0 && x <= b.width && y >= 0.0 && y <= b.height)) return 0;
  const int col = std::min(int(x), b.width - 1), row = std::min(int(y), b.height - 1);
  return values_[std::size_t(row) * std::size_t(b.width) + std::size_t(col)];
}

}  // namespace tellus
