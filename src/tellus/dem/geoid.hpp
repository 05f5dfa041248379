#pragma once
// A global geoid model: the undulation N, the height of the geoid above the WGS84 ellipsoid, on
// a regular latitude/longitude grid read through GDAL (EGM96: ../shared/data/egm96-geoid/
// egm96_15.gtx, 15 arc-minutes, -107 to 85 m). SRTM, BIL and ETOPO heights are above the geoid
// (orthometric H); the ellipsoidal height the globe needs is h = H + N.
//
// Interpolation is bilinear in latitude and longitude with longitudes wrapped, as PROJ's
// vgridshift does with the same grid (tests/unit/geoid_test.cpp compares the two).
#include <filesystem>
#include <span>
#include <vector>

#include "tellus/core/result.hpp"

namespace tellus {

class Geoid {
 public:
  // Errors: unreadable, not one band, not a global north-up latitude/longitude grid, or
  // no-data samples in it.
  static Result<Geoid> load(const std::filesystem::path& path);

  // N at (lat, lon) in degrees, metres. Latitudes clamp to +-90; longitudes wrap.
  double undulationM(double latDeg, double lonDeg) const;
  // undulationM at every point of a latitude/longitude grid, row-major: out[j * lons + i] at
  // (latsDeg[j], lonsDeg[i]). The same values, each row's and column's lookup made once (a
  // mesh's vertices). `out` holds latsDeg.size() * lonsDeg.size() values.
  void undulationsM(std::span<const double> latsDeg, std::span<const double> lonsDeg,
                    std::span<double> out) const;
  // h = H + N.
  double ellipsoidalHeightM(double orthometricM, double latDeg, double lonDeg) const {
    return orthometricM + undulationM(latDeg, lonDeg);
  }

  int columns() const { return columns_; }
  int rows() const { return rows_; }
  double stepDeg() const { return stepDeg_; }

 private:
  struct Place {  // a row's (or column's) two grid lines and where between them
    int first = 0, second = 0;
    double fraction = 0.0;
  };
  Place rowAt(double latDeg) const;
  Place columnAt(double lonDeg) const;
  double interpolate(const Place& row, const Place& column) const;

  int columns_ = 0, rows_ = 0;
  double westDeg_ = 0.0;   // longitude of column 0's samples
  double northDeg_ = 0.0;  // latitude of row 0's samples
  double stepDeg_ = 0.0;
  std::vector<float> values_;  // row-major, row 0 north, metres
};

}  // namespace tellus
