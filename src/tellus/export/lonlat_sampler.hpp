#pragma once
// Heights of a grid (one level of a store) at longitudes and latitudes: each point taken into
// the grid's CRS (directly for a latitude/longitude grid, through GDAL/PROJ for a projected
// one) and interpolated bilinearly between the four samples around it. Thread-safe: each call
// makes its own transformation.
#include <array>
#include <span>
#include <vector>

#include "tellus/core/result.hpp"
#include "tellus/dem/height_grid.hpp"

namespace tellus {

struct LonLatBox {
  double westDeg = 0.0, southDeg = 0.0, eastDeg = 0.0, northDeg = 0.0;
};

class LonLatSampler {
 public:
  // Errors: a grid without a geotransform or CRS, a CRS PROJ cannot take WGS84 points into.
  static Result<LonLatSampler> create(HeightGrid grid);

  // out[i] = height at (lonsDeg[i], latsDeg[i]), metres: bilinear between the four samples
  // around it; the outermost samples' within half a pixel beyond them (the raster's footprint);
  // longitudes wrapped for a latitude/longitude grid that goes round the globe; NaN elsewhere.
  void sample(std::span<const double> lonsDeg, std::span<const double> latsDeg,
              std::span<float> out) const;
  // The grid's samples (every `stride`-th column and row) whose WGS84 longitude and latitude
  // lie strictly inside `box` and whose heights are finite: appended to the three vectors.
  void samplesInside(const LonLatBox& box, int stride, std::vector<double>& lonsDeg,
                     std::vector<double>& latsDeg, std::vector<float>& heightsM) const;
  // How many samples of the grid lie in the box, about (from its pixel window).
  double samplesInWindow(const LonLatBox& box) const;
  // The box of WGS84 longitudes and latitudes around the grid's samples.
  const LonLatBox& bounds() const { return bounds_; }
  // Ground spacing of the grid's samples, degrees of latitude (north-south) at the centre.
  double spacingDeg() const { return spacingDeg_; }
  const HeightGrid& grid() const { return grid_; }

 private:
  HeightGrid grid_;
  bool lonLatGrid_ = false;  // the CRS is WGS84 longitude/latitude: no transformation
  bool wrapsLongitude_ = false;  // ... and its columns cover 360 degrees
  std::array<double, 6> inverse_{};  // CRS x, y -> fractional pixel (col, row) of sample centres
  LonLatBox bounds_;
  double spacingDeg_ = 0.0;
};

}  // namespace tellus

namespace tellus {

// The window of sample centres (fractional columns and rows of the grid `georef` describes,
// row 0 north) around a box of WGS84 longitudes and latitudes (its outline, every 1/16 of each
// edge, taken into the grid's CRS). Errors: no georeferencing, a CRS PROJ cannot reach.
struct PixelBox {
  double col0 = 0.0, row0 = 0.0, col1 = 0.0, row1 = 0.0;
};
Result<PixelBox> pixelBoxOf(const GeoReference& georef, const LonLatBox& box);

// The WGS84 longitude and latitude (degrees) of every sample centre of a georeferenced grid,
// row-major. Errors: no georeferencing, a CRS PROJ cannot take to WGS84, samples outside it.
Status sampleLonLats(const HeightGrid& grid, std::vector<double>& lonsDeg,
                     std::vector<double>& latsDeg);

}  // namespace tellus
