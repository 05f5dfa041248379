#include "tellus/dem/latlon_warper.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <optional>
#include <vector>

#include <gdal_utils.h>
#include <gdalwarper.h>
#include <ogr_spatialref.h>

#include <spdlog/spdlog.h>

#include "tellus/core/geotransform_check.hpp"
#include "tellus/dem/gdal_support.hpp"

namespace tellus {
namespace fs = std::filesystem;

namespace {

// Degrees of latitude per metre on the ground, roughly (to rank projected sources by
// resolution; exactness does not matter there).
constexpr double kMetresPerDegree = 111'320.0;

const OGRSpatialReference& wgs84() {
  static const OGRSpatialReference srs = [] {
    OGRSpatialReference s;
    s.SetWellKnownGeogCS("WGS84");
    s.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
    return s;
  }();
  return srs;
}

// The warp options every call shares (see the header's contract).
struct WarpOptionsDeleter {
  void operator()(GDALWarpAppOptions* o) const { GDALWarpAppOptionsFree(o); }
};
using WarpOptionsPtr = std::unique_ptr<GDALWarpAppOptions, WarpOptionsDeleter>;

// `assumeWgs84`: the source has no CRS of its own (SRTM BIL tiles without a .prj).
WarpOptionsPtr makeWarpOptions(bool assumeWgs84) {
  std::vector<const char*> argv = {"-r",  "bilinear", "-et", "0",        "-ovr",       "NONE",
                                   "-wo", "XSCALE=1", "-wo", "YSCALE=1", "-dstnodata", "nan",
                                   "-wo", "INIT_DEST=NO_DATA", "-wm", "64", "-q",
                                   // Sources and targets lie within -180..180 (checked when a
                                   // source is described; 180 E is warped at -180): no
                                   // longitude wrapping, so a WGS84 source needs no
                                   // coordinate transformation at all.
                                   "-to", "INSERT_CENTER_LONG=NO"};
  if (assumeWgs84) {
    argv.push_back("-s_srs");
    argv.push_back("EPSG:4326");
  }
  argv.push_back(nullptr);
  return WarpOptionsPtr(GDALWarpAppOptionsNew(const_cast<char**>(argv.data()), nullptr));
}

}  // namespace

Result<LatLonSource> describeLatLonSource(const fs::path& path, HeightEncoding rgbEncoding) {
  gdal::ensureRegistered();
  const std::string name = path.string();
  Result<gdal::DatasetPtr> opened = gdal::openRasterFile(
      path, "source", "a georeferenced DEM such as a GeoTIFF, an SRTM .hgt tile or a BIL/ENVI raster");
  if (!opened) return opened.error();
  gdal::DatasetPtr dataset = std::move(opened.value());
  if (dataset->GetRasterXSize() < 2 || dataset->GetRasterYSize() < 2) {
    return makeError("'{}' is {} x {} samples: a source needs at least 2 x 2", name,
                     dataset->GetRasterXSize(), dataset->GetRasterYSize());
  }
  const int bands = dataset->GetRasterCount();
  const bool rgb = (bands == 3 || bands == 4) &&
                   dataset->GetRasterBand(1)->GetRasterDataType() == GDT_Byte;
  if (rgb && rgbEncoding == HeightEncoding::Plain) {
    return makeError(
        "'{}' is an 8-bit colour image, not a height raster; if it holds RGB-encoded heights "
        "pass --encoding terrain-rgb or --encoding terrarium",
        name);
  }
  if (!rgb && bands != 1) {
    return makeError("'{}' has {} bands; a global store takes single-band height rasters or "
                     "RGB-encoded ones (3 or 4 bands of 8 bits)",
                     name, bands);
  }
  double gt[6] = {};
  if (dataset->GetGeoTransform(gt) != CE_None) {
    return makeError("'{}' has no georeferencing: a global store must know where it lies", name);
  }
  if (Status northUp = checkNorthUpGeoTransform(std::to_array(gt)); !northUp) {
    return makeError("'{}': {}", name, northUp.error().message);
  }
  const OGRSpatialReference* srs = dataset->GetSpatialRef();
  LatLonSource s;
  if (!srs) {
    // SRTM's BIL tiles come without a .prj: a grid of sub-degree cells inside the globe's
    // longitudes and latitudes is taken as WGS 84 latitude/longitude, with a warning.
    if (gridLiesWithinGlobeDegrees(std::to_array(gt), dataset->GetRasterXSize(),
                                   dataset->GetRasterYSize())) {
      spdlog::warn("'{}' has no coordinate system; its grid lies within the globe's degrees, so "
                   "it is taken as WGS 84 latitude/longitude",
                   name);
      s.assumedWgs84 = true;
      srs = &wgs84();
    } else {
      return makeError("'{}' has no coordinate system (give it one with gdal_edit.py -a_srs)",
                       name);
    }
  }
  s.path = path;
  s.readPath = path;
  s.encoding = rgb ? rgbEncoding : HeightEncoding::Plain;
  s.width = dataset->GetRasterXSize();
  s.height = dataset->GetRasterYSize();
  const double west = gt[0], north = gt[3];
  const double east = west + s.width * gt[1], south = north + s.height * gt[5];
  if (srs->IsGeographic()) {
    s.pixelBox = {west, south, east, north};
    s.sampleBox = {west + 0.5 * gt[1], south - 0.5 * gt[5], east - 0.5 * gt[1],
                   north + 0.5 * gt[5]};
    s.spacingDeg = std::min(gt[1], -gt[5]);
  } else {
    OGRSpatialReference source(*srs);
    source.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
    std::unique_ptr<OGRCoordinateTransformation> toWgs84(
        OGRCreateCoordinateTransformation(&source, &wgs84()));
    double w = 0, s2 = 0, e = 0, n = 0;
    if (!toWgs84 || !toWgs84->TransformBounds(west, south, east, north, &w, &s2, &e, &n, 21)) {
      return makeError("'{}': its coordinate system does not convert to WGS84 latitude/longitude",
                       name);
    }
    s.pixelBox = s.sampleBox = {w, s2, e, n};
    s.spacingDeg = std::min(gt[1], -gt[5]) * source.GetLinearUnits() / kMetresPerDegree;
  }
  const LatLonBox& b = s.pixelBox;
  if (!(b.westDeg >= -180.0 - s.spacingDeg && b.eastDeg <= 180.0 + s.spacingDeg &&
        b.southDeg >= -90.0 - s.spacingDeg && b.northDeg <= 90.0 + s.spacingDeg &&
        b.westDeg < b.eastDeg && b.southDeg < b.northDeg)) {
    return makeError(
        "'{}' spans longitudes {}..{} and latitudes {}..{}: a global store takes sources within "
        "-180..180 and -90..90 (turn a 0..360 grid round with gdalwarp -t_srs EPSG:4326 "
        "--config CENTER_LONG 0)",
        name, b.westDeg, b.eastDeg, b.southDeg, b.northDeg);
  }
  s.coversGlobe = b.eastDeg - b.westDeg >= 360.0 - 1e-9 && b.southDeg <= -90.0 + s.spacingDeg &&
                  b.northDeg >= 90.0 - s.spacingDeg;
  return s;
}

// Where a source's own grid lies, to measure a point's distance to its edges (edge blending).
struct LatLonSourceGrid {
  std::array<double, 6> geoTransform{};
  int width = 0, height = 0;
  bool geographic = true;
  double metresPerUnit = 1.0;  // projected sources: the CRS's linear unit
  // WGS84 longitude/latitude to the source's CRS; null when that is WGS84 longitude/latitude.
  std::unique_ptr<OGRCoordinateTransformation> fromWgs84;
};

// Sources a warper keeps open at once (each holds a file descriptor and GDAL's state).
constexpr std::size_t kMaxOpenSources = 64;

struct LatLonWarper::Impl {
  // Fills `weights` (columns * rows) with source `index`'s edge-blending weight at each sample
  // of the grid (the header's contract): 0 outside its outermost sample centres, 1 from
  // edgeBlendM metres inside them.
  void edgeWeights(int index, double westDeg, double northDeg, double stepDeg, int columns,
                   int rows, std::vector<double>& weights);

  // Opens source `index` (if it is not open) and describes it (the first time): a planet's
  // thousands of sources are opened only where the tiles warped need them, and at most
  // kMaxOpenSources at once (the least recently used is closed).
  Status ensureOpen(int index);

  std::vector<LatLonSource> sources;
  std::vector<std::optional<LatLonSourceGrid>> grids;  // per source, once described
  double edgeBlendM = 0.0;
  std::vector<double> pointX, pointY;  // scratch for edgeWeights
  std::vector<int> pointValid;
  std::vector<gdal::DatasetPtr> datasets;  // per source: open or null
  std::vector<std::uint64_t> lastUse;      // per source: the use count when last used
  std::uint64_t uses = 0;
  std::size_t openCount = 0;
  std::vector<double> scale, offset;
  std::vector<WarpOptionsPtr> options;  // per source
  GDALDriver* memDriver = nullptr;
  bool zeroYieldsToSeaFloor = false;
  std::vector<float> scratch;
  std::vector<double> weights;      // per sample: the current source's blend weight
  std::vector<double> weightSum;    // per sample: the weight taken so far (1: complete)
  std::vector<double> weightedSum;  // per sample: the weighted heights taken so far
  std::vector<double> seaShare;     // per sample: the weight of 0 m values open to a sea floor
  std::vector<std::uint64_t> finiteValues;  // per source: finite values its warps gave
};

void LatLonWarper::Impl::edgeWeights(int index, double westDeg, double northDeg, double stepDeg,
                                     int columns, int rows, std::vector<double>& out) {
  const LatLonSourceGrid& grid = *grids[std::size_t(index)];
  const std::size_t count = std::size_t(columns) * std::size_t(rows);
  pointX.resize(count);
  pointY.resize(count);
  pointValid.assign(count, TRUE);
  for (int j = 0; j < rows; ++j) {
    for (int i = 0; i < columns; ++i) {
      pointX[std::size_t(j) * std::size_t(columns) + std::size_t(i)] = westDeg + i * stepDeg;
      pointY[std::size_t(j) * std::size_t(columns) + std::size_t(i)] = northDeg - j * stepDeg;
    }
  }
  if (grid.fromWgs84) {
    // Points the transformation cannot take (beyond a projection's domain) get weight 0.
    grid.fromWgs84->Transform(static_cast<int>(count), pointX.data(), pointY.data(), nullptr,
                              pointValid.data());
  }
  const auto& gt = grid.geoTransform;
  const double unitX = std::abs(gt[1]) * (grid.geographic ? kMetresPerDegree : grid.metresPerUnit);
  const double unitY = std::abs(gt[5]) * (grid.geographic ? kMetresPerDegree : grid.metresPerUnit);
  out.resize(count);
  for (std::size_t k = 0; k < count; ++k) {
    if (!pointValid[k] || !std::isfinite(pointX[k]) || !std::isfinite(pointY[k])) {
      out[k] = 0.0;
      continue;
    }
    // Sample-centre coordinates: 0 and width - 1 are the outermost sample centres.
    const double column = (pointX[k] - gt[0]) / gt[1] - 0.5;
    const double row = (pointY[k] - gt[3]) / gt[5] - 0.5;
    const double columnsIn = std::min(column, double(grid.width - 1) - column);
    const double rowsIn = std::min(row, double(grid.height - 1) - row);
    // A degree of longitude shrinks with the latitude (the point's own, in degrees).
    const double lonScale =
        grid.geographic ? std::cos(pointY[k] * (3.14159265358979323846 / 180.0)) : 1.0;
    const double inside = std::min(columnsIn * unitX * lonScale, rowsIn * unitY);
    const double t = std::clamp(inside / edgeBlendM, 0.0, 1.0);
    out[k] = t * t * (3.0 - 2.0 * t);
  }
}

LatLonWarper::LatLonWarper(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
LatLonWarper::~LatLonWarper() = default;

const std::vector<LatLonSource>& LatLonWarper::sources() const { return impl_->sources; }

std::uint64_t LatLonWarper::finiteValuesFrom(int source) const {
  const std::vector<std::uint64_t>& counts = impl_->finiteValues;
  return source >= 0 && std::size_t(source) < counts.size() ? counts[std::size_t(source)] : 0;
}

namespace {
// The grid of an opened source and how WGS84 points map into it (edge blending).
Result<LatLonSourceGrid> describeGrid(GDALDataset& dataset, const LatLonSource& source) {
  LatLonSourceGrid grid;
  if (dataset.GetGeoTransform(grid.geoTransform.data()) != CE_None) {
    return makeError("'{}' has no georeferencing", source.path.string());
  }
  grid.width = dataset.GetRasterXSize();
  grid.height = dataset.GetRasterYSize();
  const OGRSpatialReference* srs = source.assumedWgs84 ? nullptr : dataset.GetSpatialRef();
  if (!srs) return grid;  // taken as WGS84 longitude/latitude (describeLatLonSource)
  OGRSpatialReference own(*srs);
  own.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
  grid.geographic = own.IsGeographic();
  if (!grid.geographic) grid.metresPerUnit = own.GetLinearUnits();
  if (grid.geographic && own.IsSame(&wgs84())) return grid;
  grid.fromWgs84.reset(OGRCreateCoordinateTransformation(&wgs84(), &own));
  if (!grid.fromWgs84) {
    return makeError("'{}': WGS84 points do not convert to its coordinate system",
                     source.path.string());
  }
  return grid;
}
}  // namespace

Result<std::unique_ptr<LatLonWarper>> LatLonWarper::open(std::vector<LatLonSource> sources,
                                                        bool zeroYieldsToSeaFloor,
                                                        double edgeBlendM) {
  gdal::ensureRegistered();
  if (!(edgeBlendM >= 0.0) || !std::isfinite(edgeBlendM)) {
    return makeError("the edge blending band must be 0 or more metres, not {}", edgeBlendM);
  }
  auto impl = std::make_unique<Impl>();
  impl->zeroYieldsToSeaFloor = zeroYieldsToSeaFloor;
  impl->edgeBlendM = edgeBlendM;
  for (const LatLonSource& s : sources) {
    if (s.encoding != HeightEncoding::Plain && s.readPath == s.path) {
      return makeError("internal error: '{}' is RGB-encoded and has no decoded copy",
                       s.path.string());
    }
  }
  const std::size_t count = sources.size();
  impl->grids.resize(count);
  impl->datasets.resize(count);
  impl->lastUse.assign(count, 0);
  impl->scale.assign(count, 1.0);
  impl->offset.assign(count, 0.0);
  impl->options.resize(count);
  impl->sources = std::move(sources);
  impl->memDriver = GetGDALDriverManager()->GetDriverByName("MEM");
  if (!impl->memDriver) return makeError("GDAL has no MEM driver");
  return std::unique_ptr<LatLonWarper>(new LatLonWarper(std::move(impl)));
}

Status LatLonWarper::Impl::ensureOpen(int index) {
  const std::size_t i = std::size_t(index);
  lastUse[i] = ++uses;
  if (datasets[i]) return {};
  if (openCount >= kMaxOpenSources) {
    std::size_t oldest = datasets.size();
    for (std::size_t k = 0; k < datasets.size(); ++k) {
      if (datasets[k] && (oldest == datasets.size() || lastUse[k] < lastUse[oldest])) oldest = k;
    }
    datasets[oldest].reset();
    --openCount;
  }
  const LatLonSource& s = sources[i];
  gdal::DatasetPtr dataset(GDALDataset::Open(s.readPath.c_str(), GDAL_OF_RASTER | GDAL_OF_READONLY));
  if (!dataset) return makeError("'{}': {}", s.path.string(), gdal::lastError());
  if (!grids[i]) {
    GDALRasterBand* band = dataset->GetRasterBand(1);
    int has = 0;
    const double bandScale = band->GetScale(&has);
    scale[i] = has ? bandScale : 1.0;
    const double bandOffset = band->GetOffset(&has);
    offset[i] = has ? bandOffset : 0.0;
    Result<LatLonSourceGrid> grid = describeGrid(*dataset, s);
    if (!grid) return grid.error();
    grids[i] = std::move(grid.value());
    options[i] = makeWarpOptions(s.assumedWgs84);
    if (!options[i]) return makeError("cannot set up GDAL's warper: {}", gdal::lastError());
  }
  datasets[i] = std::move(dataset);
  ++openCount;
  return {};
}

namespace {
struct WarpProgress {
  const std::function<void(int, double)>* report;
  int source;
};
int CPL_STDCALL reportWarpProgress(double complete, const char*, void* data) {
  const auto* p = static_cast<const WarpProgress*>(data);
  (*p->report)(p->source, std::clamp(complete, 0.0, 1.0));
  return TRUE;
}
}  // namespace

Status LatLonWarper::warp(double westDeg, double northDeg, double stepDeg, int columns, int rows,
                          std::span<const int> use, std::span<float> out,
                          const std::function<void(int, double)>& progress) {
  if (columns < 1 || rows < 1 || out.size() != std::size_t(columns) * std::size_t(rows) ||
      !(stepDeg > 0.0)) {
    return makeError("internal error: warp of {} x {} samples into {} values", columns, rows,
                     out.size());
  }
  // Per sample: the weight taken so far and the weighted heights (header: edge blending).
  // Without blending every weight is 1, and a sample takes its first value exactly.
  Impl& m = *impl_;
  const std::size_t count = out.size();
  m.weightSum.assign(count, 0.0);
  m.weightedSum.assign(count, 0.0);
  m.seaShare.assign(count, 0.0);
  std::size_t missing = count;  // samples whose weights do not sum to 1 yet
  std::size_t open = 0;         // samples with a 0 m share that a later sea floor may take
  for (int index : use) {
    if (missing == 0 && open == 0) break;
    if (Status opened = m.ensureOpen(index); !opened) return opened;
    const LatLonSource& described = m.sources[std::size_t(index)];
    const bool blend = m.edgeBlendM > 0.0 && !described.coversGlobe;
    if (blend) {
      m.edgeWeights(index, westDeg, northDeg, stepDeg, columns, rows, m.weights);
    }
    gdal::DatasetPtr target(
        m.memDriver->Create("", columns, rows, 1, GDT_Float32, nullptr));
    if (!target) return makeError("cannot create a warp target: {}", gdal::lastError());
    // Pixel-is-area cells centred on the sample points.
    double gt[6] = {westDeg - 0.5 * stepDeg, stepDeg, 0.0, northDeg + 0.5 * stepDeg, 0.0,
                    -stepDeg};
    target->SetGeoTransform(gt);
    target->SetProjection(gdal::wgs84Wkt().c_str());
    target->GetRasterBand(1)->SetNoDataValue(std::numeric_limits<double>::quiet_NaN());
    // The warper only touches the part of the target its source reaches: the rest must read
    // as "no value", not as the MEM driver's zeros.
    target->GetRasterBand(1)->Fill(std::numeric_limits<double>::quiet_NaN());
    GDALDatasetH source = GDALDataset::ToHandle(m.datasets[std::size_t(index)].get());
    int usageError = 0;
    CPLErrorReset();
    WarpProgress warpProgress{&progress, index};
    GDALWarpAppOptions* options = m.options[std::size_t(index)].get();
    GDALWarpAppOptionsSetProgress(options, progress ? reportWarpProgress : nullptr,
                                  progress ? &warpProgress : nullptr);
    GDALDatasetH result = GDALWarp(nullptr, GDALDataset::ToHandle(target.get()), 1, &source,
                                   options, &usageError);
    GDALWarpAppOptionsSetProgress(options, nullptr, nullptr);
    if (progress) progress(index, 1.0);
    if (!result) {
      return makeError("'{}': GDAL's warper failed: {}", described.path.string(),
                       gdal::lastError());
    }
    m.scratch.resize(count);
    if (target->GetRasterBand(1)->RasterIO(GF_Read, 0, 0, columns, rows, m.scratch.data(),
                                           columns, rows, GDT_Float32, 0, 0) != CE_None) {
      return makeError("cannot read a warped grid: {}", gdal::lastError());
    }
    const double scale = m.scale[std::size_t(index)], offset = m.offset[std::size_t(index)];
    if (m.finiteValues.size() != m.sources.size()) m.finiteValues.assign(m.sources.size(), 0);
    for (std::size_t i = 0; i < count; ++i) {
      if (!std::isfinite(m.scratch[i])) continue;
      const float value = float(double(m.scratch[i]) * scale + offset);
      if (!std::isfinite(value)) continue;  // beyond float once scaled: no height
      ++m.finiteValues[std::size_t(index)];
      if (m.seaShare[i] > 0.0 && value < 0.0f) {
        // A sea floor under a finer source's flat sea takes the zeros' share (they added 0).
        m.weightedSum[i] += m.seaShare[i] * double(value);
        m.seaShare[i] = 0.0;
        --open;
      }
      if (m.weightSum[i] >= 1.0) continue;
      const double weight = blend ? m.weights[i] : 1.0;
      if (weight <= 0.0) continue;
      const double share = (1.0 - m.weightSum[i]) * weight;
      m.weightedSum[i] += share * double(value);
      m.weightSum[i] = weight >= 1.0 ? 1.0 : m.weightSum[i] + share;
      if (m.weightSum[i] >= 1.0) --missing;
      if (m.zeroYieldsToSeaFloor && value == 0.0f) {
        if (m.seaShare[i] == 0.0) ++open;
        m.seaShare[i] += share;
      }
    }
  }
  // Exactly the value where one source gave it all; the weighted mean where sources shared it;
  // NaN where none had a value.
  for (std::size_t i = 0; i < count; ++i) {
    const double w = m.weightSum[i];
    out[i] = w >= 1.0 ? float(m.weightedSum[i])
             : w > 0.0 ? float(m.weightedSum[i] / w)
                       : std::numeric_limits<float>::quiet_NaN();
  }
  return {};
}

}  // namespace tellus
