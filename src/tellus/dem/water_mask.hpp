#pragma once
// Where the water is: an 8-bit latitude/longitude raster of one band, 0 for dry land, 255
// for water, values between for coasts and marsh, as NASA's BlueMarbleWater.jpg (with its .jgw
// world file) has it. For quantized-mesh's watermask extension.
#include <cstdint>
#include <filesystem>
#include <vector>

#include "tellus/core/result.hpp"
#include "tellus/dem/lat_lon_raster.hpp"

namespace tellus {

class WaterMask {
 public:
  // Errors name the file (lat_lon_raster.hpp's, more than one band, more than 65,536 pixels a
  // side).
  static Result<WaterMask> load(const std::filesystem::path& path);

  // The nearest pixel's value at a longitude and latitude (degrees): longitudes wrap when the
  // mask goes round the globe; outside it, 0 (land: no water known there).
  std::uint8_t at(double lonDeg, double latDeg) const;
  const LatLonRasterBounds& bounds() const { return bounds_; }

 private:
  LatLonRasterBounds bounds_;
  std::vector<std::uint8_t> values_;  // row-major, row 0 north
  bool wraps_ = false;
};

}  // namespace tellus
