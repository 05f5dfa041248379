#include "tellus/dem/geoid.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>

#include "tellus/core/geotransform_check.hpp"
#include "tellus/dem/gdal_support.hpp"

namespace tellus {

Result<Geoid> Geoid::load(const std::filesystem::path& path) {
  gdal::ensureRegistered();
  Result<gdal::DatasetPtr> opened = gdal::openRasterFile(
      path, "geoid", "a global geoid grid such as EGM96's egm96_15.gtx (PROJ's .gtx or a GeoTIFF)");
  if (!opened) return opened.error();
  gdal::DatasetPtr dataset = std::move(opened.value());
  if (dataset->GetRasterCount() != 1) {
    return makeError("geoid '{}': {} bands, a geoid grid has one", path.string(),
                     dataset->GetRasterCount());
  }
  double transform[6] = {};
  if (dataset->GetGeoTransform(transform) != CE_None) {
    return makeError("geoid '{}' has no georeferencing (a geoid grid covers the globe in "
                     "latitude and longitude)",
                     path.string());
  }
  if (Status northUp = checkNorthUpGeoTransform(std::to_array(transform)); !northUp) {
    return makeError("geoid '{}': {}", path.string(), northUp.error().message);
  }
  if (std::abs(transform[1] + transform[5]) > 1e-12) {
    return makeError("geoid '{}': its cells are {} x {} degrees, not square", path.string(),
                     transform[1], -transform[5]);
  }
  Geoid geoid;
  geoid.columns_ = dataset->GetRasterXSize();
  geoid.rows_ = dataset->GetRasterYSize();
  geoid.stepDeg_ = transform[1];
  // Samples are at the cell centres (GDAL's pixel-is-area convention).
  geoid.westDeg_ = transform[0] + 0.5 * geoid.stepDeg_;
  geoid.northDeg_ = transform[3] - 0.5 * geoid.stepDeg_;
  const double southDeg = geoid.northDeg_ - (geoid.rows_ - 1) * geoid.stepDeg_;
  if (std::abs(geoid.columns_ * geoid.stepDeg_ - 360.0) > 1e-6 ||
      std::abs(geoid.northDeg_ - 90.0) > 1e-6 || std::abs(southDeg + 90.0) > 1e-6) {
    return makeError(
        "geoid '{}': {} x {} samples of {} degrees from ({}, {}) do not cover the globe pole to "
        "pole",
        path.string(), geoid.columns_, geoid.rows_, geoid.stepDeg_, geoid.northDeg_,
        geoid.westDeg_);
  }
  // EGM2008 at 1 arc-minute, the finest global model in use, has 233 million samples.
  constexpr std::uint64_t kMaxSamples = 300'000'000;
  if (std::uint64_t(geoid.columns_) * std::uint64_t(geoid.rows_) > kMaxSamples) {
    return makeError("geoid '{}': {} x {} samples, more than the {} a geoid grid may have",
                     path.string(), geoid.columns_, geoid.rows_, kMaxSamples);
  }
  geoid.values_.resize(std::size_t(geoid.columns_) * std::size_t(geoid.rows_));
  GDALRasterBand* band = dataset->GetRasterBand(1);
  if (band->RasterIO(GF_Read, 0, 0, geoid.columns_, geoid.rows_, geoid.values_.data(),
                     geoid.columns_, geoid.rows_, GDT_Float32, 0, 0) != CE_None) {
    return makeError("geoid '{}': {}", path.string(), gdal::lastError());
  }
  int hasNoData = 0;
  const double noData = band->GetNoDataValue(&hasNoData);
  for (float v : geoid.values_) {
    if (!std::isfinite(v) || (hasNoData && double(v) == double(float(noData)))) {
      return makeError("geoid '{}': no-data or non-finite samples in the grid", path.string());
    }
  }
  return geoid;
}

Geoid::Place Geoid::rowAt(double latDeg) const {
  const double row = std::clamp((northDeg_ - latDeg) / stepDeg_, 0.0, double(rows_ - 1));
  const int r0 = std::min(int(row), rows_ - 2);
  return {r0, r0 + 1, row - r0};
}

Geoid::Place Geoid::columnAt(double lonDeg) const {
  double column = std::fmod((lonDeg - westDeg_) / stepDeg_, double(columns_));
  if (column < 0.0) column += columns_;
  const int c0 = std::min(int(column), columns_ - 1);
  return {c0, (c0 + 1) % columns_, column - c0};  // wraps across the antimeridian
}

double Geoid::interpolate(const Place& row, const Place& column) const {
  const auto at = [&](int c, int r) {
    return double(values_[std::size_t(r) * std::size_t(columns_) + std::size_t(c)]);
  };
  const double fx = column.fraction, fy = row.fraction;
  const double north = at(column.first, row.first) * (1.0 - fx) + at(column.second, row.first) * fx;
  const double south =
      at(column.first, row.second) * (1.0 - fx) + at(column.second, row.second) * fx;
  return north * (1.0 - fy) + south * fy;
}

double Geoid::undulationM(double latDeg, double lonDeg) const {
  return interpolate(rowAt(latDeg), columnAt(lonDeg));
}

void Geoid::undulationsM(std::span<const double> latsDeg, std::span<const double> lonsDeg,
                         std::span<double> out) const {
  std::vector<Place> columns(lonsDeg.size());
  for (std::size_t i = 0; i < lonsDeg.size(); ++i) columns[i] = columnAt(lonsDeg[i]);
  for (std::size_t j = 0; j < latsDeg.size(); ++j) {
    const Place row = rowAt(latsDeg[j]);
    double* line = out.data() + j * lonsDeg.size();
    for (std::size_t i = 0; i < lonsDeg.size(); ++i) line[i] = interpolate(row, columns[i]);
  }
}

}  // namespace tellus
