#include "tellus/export/lonlat_sampler.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <vector>

#include <cpl_error.h>
#include <ogr_spatialref.h>

namespace tellus {
namespace {

OGRSpatialReference wgs84LonLat() {
  OGRSpatialReference s;
  s.SetWellKnownGeogCS("WGS84");
  s.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
  return s;
}

struct TransformDeleter {
  void operator()(OGRCoordinateTransformation* t) const {
    OGRCoordinateTransformation::DestroyCT(t);
  }
};
using TransformPtr = std::unique_ptr<OGRCoordinateTransformation, TransformDeleter>;

Result<OGRSpatialReference> gridCrs(const GeoReference& georef) {
  OGRSpatialReference crs;
  if (crs.importFromWkt(georef.crsWkt.c_str()) != OGRERR_NONE) {
    return makeError("the grid's CRS cannot be read ('{}')", georef.crsName);
  }
  crs.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
  return crs;
}

Result<TransformPtr> makeTransform(const OGRSpatialReference& from, const OGRSpatialReference& to) {
  TransformPtr t(OGRCreateCoordinateTransformation(&from, &to));
  if (!t) return makeError("PROJ cannot transform between WGS84 and the grid's CRS");
  return t;
}

}  // namespace

Result<LonLatSampler> LonLatSampler::create(HeightGrid grid) {
  const GeoReference& georef = grid.georef;
  if (!georef.hasGeoTransform || georef.crsWkt.empty()) {
    return makeError("the grid has no georeferencing (a geotransform and a CRS are needed)");
  }
  const auto& gt = georef.geoTransform;
  const double det = gt[1] * gt[5] - gt[2] * gt[4];
  if (det == 0.0 || !std::isfinite(det)) return makeError("the grid's geotransform is singular");
  LonLatSampler sampler;
  // Inverse of (col + 0.5, row + 0.5) -> (x, y): sample centres of a pixel-is-area raster.
  sampler.inverse_ = {gt[5] / det, -gt[2] / det, -gt[4] / det, gt[1] / det, gt[0], gt[3]};

  Result<OGRSpatialReference> crs = gridCrs(georef);
  if (!crs) return crs.error();
  const OGRSpatialReference wgs84 = wgs84LonLat();
  sampler.lonLatGrid_ = crs->IsGeographic() && crs->IsSameGeogCS(&wgs84);

  // Bounds: the grid's outline (every 16th sample along each edge) in WGS84.
  std::vector<double> xs, ys;
  auto addSample = [&](double col, double row) {
    xs.push_back(gt[0] + (col + 0.5) * gt[1] + (row + 0.5) * gt[2]);
    ys.push_back(gt[3] + (col + 0.5) * gt[4] + (row + 0.5) * gt[5]);
  };
  const int w = grid.width - 1, h = grid.height - 1;
  for (int i = 0; i <= 16; ++i) {
    addSample(w * i / 16.0, 0);
    addSample(w * i / 16.0, h);
    addSample(0, h * i / 16.0);
    addSample(w, h * i / 16.0);
  }
  if (!sampler.lonLatGrid_) {
    Result<TransformPtr> toWgs84 = makeTransform(crs.value(), wgs84);
    if (!toWgs84) return toWgs84.error();
    if (!toWgs84.value()->Transform(int(xs.size()), xs.data(), ys.data())) {
      return makeError("the grid's outline cannot be taken to WGS84 longitudes and latitudes");
    }
  }
  sampler.bounds_ = {*std::min_element(xs.begin(), xs.end()), *std::min_element(ys.begin(), ys.end()),
                     *std::max_element(xs.begin(), xs.end()), *std::max_element(ys.begin(), ys.end())};
  sampler.spacingDeg_ = (sampler.bounds_.northDeg - sampler.bounds_.southDeg) / std::max(1, h);
  // A latitude/longitude grid whose columns go once round the globe: longitudes wrap (the
  // antimeridian lies between its last column and its first).
  sampler.wrapsLongitude_ = sampler.lonLatGrid_ && gt[2] == 0.0 && gt[4] == 0.0 &&
                            std::abs(std::abs(gt[1]) * grid.width - 360.0) < 1e-6;
  sampler.grid_ = std::move(grid);
  return sampler;
}

void LonLatSampler::sample(std::span<const double> lonsDeg, std::span<const double> latsDeg,
                           std::span<float> out) const {
  std::vector<double> xs(lonsDeg.begin(), lonsDeg.end()), ys(latsDeg.begin(), latsDeg.end());
  std::vector<int> ok(xs.size(), 1);
  if (!lonLatGrid_) {
    // Made per call: OGR transformations are not thread-safe.
    Result<OGRSpatialReference> crs = gridCrs(grid_.georef);
    Result<TransformPtr> toGrid = crs ? makeTransform(wgs84LonLat(), crs.value())
                                      : Result<TransformPtr>(crs.error());
    if (!toGrid) {
      std::fill(out.begin(), out.end(), std::numeric_limits<float>::quiet_NaN());
      return;
    }
    // Points outside a projected CRS's domain (the globe's level-0 tiles around a UTM grid) are
    // expected: they come back not ok and sample as NaN, without PROJ's messages on stderr.
    CPLPushErrorHandler(CPLQuietErrorHandler);
    toGrid.value()->Transform(int(xs.size()), xs.data(), ys.data(), nullptr, ok.data());
    CPLPopErrorHandler();
  }
  const auto& inv = inverse_;
  for (std::size_t i = 0; i < xs.size(); ++i) {
    out[i] = std::numeric_limits<float>::quiet_NaN();
    if (!ok[i]) continue;
    const double dx = xs[i] - inv[4], dy = ys[i] - inv[5];
    const double col = inv[0] * dx + inv[1] * dy - 0.5;
    const double row = inv[2] * dx + inv[3] * dy - 0.5;
    // Points within the raster's own footprint (half a pixel beyond the outermost sample
    // centres) take the outermost samples' heights: no cliff at a data edge, nor at the poles
    // of a global grid. A global grid's columns wrap round the antimeridian.
    constexpr double kHalf = 0.5 + 1e-9;
    const int w = grid_.width, hgt = grid_.height;
    if (!(row >= -kHalf && row <= hgt - 1 + kHalf)) continue;
    if (!wrapsLongitude_ && !(col >= -kHalf && col <= w - 1 + kHalf)) continue;
    const double r = std::clamp(row, 0.0, double(hgt - 1));
    const int r0 = std::min(int(r), std::max(hgt - 2, 0)), r1 = std::min(r0 + 1, hgt - 1);
    const double fr = r - r0;
    int c0 = 0, c1 = 0;
    double fc = 0.0;
    if (wrapsLongitude_) {
      const double c = col - std::floor(col / w) * w;  // 0 <= c < w
      c0 = std::min(int(c), w - 1);
      c1 = (c0 + 1) % w;
      fc = c - c0;
    } else {
      const double c = std::clamp(col, 0.0, double(w - 1));
      c0 = std::min(int(c), std::max(w - 2, 0));
      c1 = std::min(c0 + 1, w - 1);
      fc = c - c0;
    }
    const double top = grid_.at(c0, r0) * (1.0 - fc) + grid_.at(c1, r0) * fc;
    const double bottom = grid_.at(c0, r1) * (1.0 - fc) + grid_.at(c1, r1) * fc;
    out[i] = float(top * (1.0 - fr) + bottom * fr);
  }
}

namespace {

// The window of sample indices (inclusive, clamped to the grid) around a box, with one sample
// to spare on each side; empty (col0 > col1) when the box misses the grid.
struct SampleWindow {
  int col0 = 0, row0 = 0, col1 = -1, row1 = -1;
};

SampleWindow windowOf(const HeightGrid& grid, const LonLatBox& box) {
  Result<PixelBox> pixels = pixelBoxOf(grid.georef, box);
  // A box PROJ cannot take into the grid's CRS (a level-0 tile around a UTM grid): the whole
  // grid, whose samples are then tested one by one.
  if (!pixels) return {0, 0, grid.width - 1, grid.height - 1};
  const auto clampIndex = [](double value, int last) {
    if (!std::isfinite(value)) return value > 0 ? last : 0;
    return int(std::clamp(value, -1.0, double(last) + 1.0));
  };
  SampleWindow w;
  w.col0 = std::max(0, clampIndex(std::floor(pixels->col0) - 1, grid.width - 1));
  w.col1 = std::min(grid.width - 1, clampIndex(std::ceil(pixels->col1) + 1, grid.width - 1));
  w.row0 = std::max(0, clampIndex(std::floor(pixels->row0) - 1, grid.height - 1));
  w.row1 = std::min(grid.height - 1, clampIndex(std::ceil(pixels->row1) + 1, grid.height - 1));
  if (pixels->col1 < -1.0 || pixels->row1 < -1.0 || pixels->col0 > grid.width ||
      pixels->row0 > grid.height) {
    return {};
  }
  return w;
}

}  // namespace

double LonLatSampler::samplesInWindow(const LonLatBox& box) const {
  const SampleWindow w = windowOf(grid_, box);
  if (w.col0 > w.col1 || w.row0 > w.row1) return 0.0;
  return double(w.col1 - w.col0 + 1) * double(w.row1 - w.row0 + 1);
}

void LonLatSampler::samplesInside(const LonLatBox& box, int stride, std::vector<double>& lonsDeg,
                                  std::vector<double>& latsDeg, std::vector<float>& heightsM) const {
  const SampleWindow w = windowOf(grid_, box);
  if (w.col0 > w.col1 || w.row0 > w.row1) return;
  stride = std::max(stride, 1);
  // Sample centres in the grid's CRS, then (projected grids) in WGS84.
  std::vector<double> xs, ys;
  std::vector<float> hs;
  const auto& gt = grid_.georef.geoTransform;
  for (int row = w.row0 - w.row0 % stride; row <= w.row1; row += stride) {
    if (row < w.row0) continue;
    for (int col = w.col0 - w.col0 % stride; col <= w.col1; col += stride) {
      if (col < w.col0) continue;
      const float h = grid_.at(col, row);
      if (!std::isfinite(h)) continue;
      xs.push_back(gt[0] + (col + 0.5) * gt[1] + (row + 0.5) * gt[2]);
      ys.push_back(gt[3] + (col + 0.5) * gt[4] + (row + 0.5) * gt[5]);
      hs.push_back(h);
    }
  }
  std::vector<int> ok(xs.size(), 1);
  if (!lonLatGrid_) {
    Result<OGRSpatialReference> crs = gridCrs(grid_.georef);
    Result<TransformPtr> toWgs84 = crs ? makeTransform(crs.value(), wgs84LonLat())
                                       : Result<TransformPtr>(crs.error());
    if (!toWgs84) return;
    CPLPushErrorHandler(CPLQuietErrorHandler);
    toWgs84.value()->Transform(int(xs.size()), xs.data(), ys.data(), nullptr, ok.data());
    CPLPopErrorHandler();
  }
  for (std::size_t i = 0; i < xs.size(); ++i) {
    if (!ok[i] || !(xs[i] > box.westDeg && xs[i] < box.eastDeg && ys[i] > box.southDeg &&
                    ys[i] < box.northDeg)) {
      continue;
    }
    lonsDeg.push_back(xs[i]);
    latsDeg.push_back(ys[i]);
    heightsM.push_back(hs[i]);
  }
}

}  // namespace tellus

namespace tellus {

Result<PixelBox> pixelBoxOf(const GeoReference& georef, const LonLatBox& box) {
  if (!georef.hasGeoTransform || georef.crsWkt.empty()) {
    return makeError("the store has no georeferencing (a geotransform and a CRS are needed)");
  }
  const auto& gt = georef.geoTransform;
  const double det = gt[1] * gt[5] - gt[2] * gt[4];
  if (det == 0.0 || !std::isfinite(det)) return makeError("the store's geotransform is singular");
  std::vector<double> xs, ys;
  for (int i = 0; i <= 16; ++i) {
    const double lon = box.westDeg + (box.eastDeg - box.westDeg) * i / 16.0;
    const double lat = box.southDeg + (box.northDeg - box.southDeg) * i / 16.0;
    xs.insert(xs.end(), {lon, lon, box.westDeg, box.eastDeg});
    ys.insert(ys.end(), {box.southDeg, box.northDeg, lat, lat});
  }
  Result<OGRSpatialReference> crs = gridCrs(georef);
  if (!crs) return crs.error();
  const OGRSpatialReference wgs84 = wgs84LonLat();
  if (!(crs->IsGeographic() && crs->IsSameGeogCS(&wgs84))) {
    Result<TransformPtr> toGrid = makeTransform(wgs84, crs.value());
    if (!toGrid) return toGrid.error();
    if (!toGrid.value()->Transform(int(xs.size()), xs.data(), ys.data())) {
      return makeError("the region cannot be taken into the store's CRS");
    }
  }
  PixelBox pixels{std::numeric_limits<double>::max(), std::numeric_limits<double>::max(),
                  -std::numeric_limits<double>::max(), -std::numeric_limits<double>::max()};
  for (std::size_t i = 0; i < xs.size(); ++i) {
    const double dx = xs[i] - gt[0], dy = ys[i] - gt[3];
    const double col = (gt[5] * dx - gt[2] * dy) / det - 0.5;
    const double row = (-gt[4] * dx + gt[1] * dy) / det - 0.5;
    pixels.col0 = std::min(pixels.col0, col);
    pixels.col1 = std::max(pixels.col1, col);
    pixels.row0 = std::min(pixels.row0, row);
    pixels.row1 = std::max(pixels.row1, row);
  }
  return pixels;
}

}  // namespace tellus

namespace tellus {

Status sampleLonLats(const HeightGrid& grid, std::vector<double>& lonsDeg,
                     std::vector<double>& latsDeg) {
  const GeoReference& georef = grid.georef;
  if (!georef.hasGeoTransform || georef.crsWkt.empty()) {
    return makeError("the grid has no georeferencing (a geotransform and a CRS are needed)");
  }
  const auto& gt = georef.geoTransform;
  const std::size_t count = std::size_t(grid.width) * std::size_t(grid.height);
  lonsDeg.resize(count);
  latsDeg.resize(count);
  for (int row = 0; row < grid.height; ++row) {
    for (int col = 0; col < grid.width; ++col) {
      const std::size_t k = std::size_t(row) * std::size_t(grid.width) + std::size_t(col);
      lonsDeg[k] = gt[0] + (col + 0.5) * gt[1] + (row + 0.5) * gt[2];
      latsDeg[k] = gt[3] + (col + 0.5) * gt[4] + (row + 0.5) * gt[5];
    }
  }
  Result<OGRSpatialReference> crs = gridCrs(georef);
  if (!crs) return crs.error();
  const OGRSpatialReference wgs84 = wgs84LonLat();
  if (crs->IsGeographic() && crs->IsSameGeogCS(&wgs84)) return {};
  Result<TransformPtr> toWgs84 = makeTransform(crs.value(), wgs84);
  if (!toWgs84) return toWgs84.error();
  std::vector<int> ok(count, 1);
  CPLPushErrorHandler(CPLQuietErrorHandler);
  toWgs84.value()->Transform(int(count), lonsDeg.data(), latsDeg.data(), nullptr, ok.data());
  CPLPopErrorHandler();
  if (std::find(ok.begin(), ok.end(), 0) != ok.end()) {
    return makeError("some of the grid's samples cannot be taken to WGS84 longitudes and latitudes");
  }
  return {};
}

}  // namespace tellus
