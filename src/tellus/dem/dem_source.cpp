#include "tellus/dem/dem_source.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <string>
#include <unordered_map>

#include <cpl_string.h>
#include <gdal_alg.h>
#include <gdal_utils.h>
#include <ogr_spatialref.h>
#include <spdlog/spdlog.h>

#include "tellus/core/geotransform_check.hpp"
#include "tellus/core/geodesy.hpp"
#include "tellus/core/input_file.hpp"
#include "tellus/core/memory_budget.hpp"
#include "tellus/core/progress.hpp"
#include "tellus/core/scratch_folder.hpp"
#include "tellus/dem/gdal_support.hpp"
#include "tellus/dem/georeference_check.hpp"
#include "tellus/dem/raster_diagnosis.hpp"

namespace tellus {
namespace fs = std::filesystem;

namespace {

constexpr double kImplausibleHeightM = 1e6;  // |h| at or above this is treated as a void
// The largest block (all bands of one GDAL block) a DEM may have: a strip of a raster of 2^24
// samples a side in 4 float bands needs 256 MiB.
constexpr double kMaxBlockBytes = double(std::uint64_t(1) << 30);

// Rows per read when scanning the whole input: 256, fewer for rasters so wide that 256 rows
// would exceed 16 M samples (64 MiB).
// Local void filling (DemSource::fillVoidsLocally): blocks of this many samples a side that
// hold voids are filled from a window reaching kFillMargin samples beyond them; beyond this
// many voids (or a quarter of the samples) the whole raster is filled at once.
constexpr int kFillBlock = 256;
constexpr int kFillMargin = 256;
constexpr std::size_t kMaxLocallyFilledVoids = std::size_t(1) << 22;

int scanRows(int width) {
  return int(std::clamp<std::int64_t>((std::int64_t(1) << 24) / std::max(width, 1), 1, 256));
}

int CPL_STDCALL reportProgress(double complete, const char*, void* progress) {
  static_cast<Progress*>(progress)->set(std::uint64_t(complete * 1000.0));
  return TRUE;
}

Result<gdal::DatasetPtr> openRaster(const fs::path& path) {
  // A FIFO or device would block GDAL for ever or stream without end.
  if (Status regular = checkRegularInput(path); !regular) return regular.error();
  CPLErrorReset();
  gdal::DatasetPtr dataset(GDALDataset::FromHandle(
      GDALOpenEx(path.c_str(), GDAL_OF_RASTER | GDAL_OF_READONLY, nullptr, nullptr, nullptr)));
  if (!dataset) {
    return makeError("cannot read '{}' as a raster: {}", path.string(),
                     explainUnreadableRaster(path, gdal::lastErrorMessage()));
  }
  if (dataset->GetRasterCount() < 1 || dataset->GetRasterXSize() < 2 ||
      dataset->GetRasterYSize() < 2) {
    return makeError("cannot use '{}': a DEM needs at least one band of 2x2 samples",
                     path.string());
  }
  return dataset;
}

// Every input of a mosaic needs a geotransform, the same CRS, band count and pixel size.
Status checkMosaicCompatible(const std::vector<gdal::DatasetPtr>& datasets,
                             const std::vector<fs::path>& paths) {
  std::array<double, 6> firstGt{};
  for (size_t i = 0; i < datasets.size(); ++i) {
    std::array<double, 6> gt{};
    if (datasets[i]->GetGeoTransform(gt.data()) != CE_None) {
      return makeError("cannot mosaic '{}': it has no georeferencing", paths[i].string());
    }
    if (i == 0) {
      firstGt = gt;
      continue;
    }
    const OGRSpatialReference* a = datasets[0]->GetSpatialRef();
    const OGRSpatialReference* b = datasets[i]->GetSpatialRef();
    if ((a == nullptr) != (b == nullptr) || (a && !a->IsSame(b))) {
      return makeError("cannot mosaic '{}' with '{}': different coordinate reference systems",
                       paths[i].string(), paths[0].string());
    }
    if (datasets[i]->GetRasterCount() != datasets[0]->GetRasterCount()) {
      return makeError("cannot mosaic '{}' with '{}': different band counts", paths[i].string(),
                       paths[0].string());
    }
    const double tolerance = 1e-9 * std::max(std::abs(firstGt[1]), std::abs(firstGt[5]));
    if (std::abs(gt[1] - firstGt[1]) > tolerance || std::abs(gt[5] - firstGt[5]) > tolerance) {
      return makeError("cannot mosaic '{}' with '{}': different sample spacing", paths[i].string(),
                       paths[0].string());
    }
  }
  return {};
}

Result<gdal::DatasetPtr> buildMosaic(std::vector<gdal::DatasetPtr>& datasets,
                                     const std::vector<fs::path>& paths) {
  if (Status compatible = checkMosaicCompatible(datasets, paths); !compatible) {
    return compatible.error();
  }
  std::vector<GDALDatasetH> handles;
  for (auto& dataset : datasets) handles.push_back(GDALDataset::ToHandle(dataset.get()));
  GDALBuildVRTOptions* options = GDALBuildVRTOptionsNew(nullptr, nullptr);
  int usageError = 0;
  GDALDatasetH vrt =
      GDALBuildVRT("", int(handles.size()), handles.data(), nullptr, options, &usageError);
  GDALBuildVRTOptionsFree(options);
  if (!vrt) return makeError("cannot mosaic the inputs: {}", gdal::lastError());
  return gdal::DatasetPtr(GDALDataset::FromHandle(vrt));
}

// Metres per unit of the band's values (1 unless the band says feet).
double verticalUnitToMetres(GDALRasterBand* band) {
  std::string unit = band->GetUnitType() ? band->GetUnitType() : "";
  std::transform(unit.begin(), unit.end(), unit.begin(), ::tolower);
  if (unit == "ft" || unit == "foot" || unit == "feet" || unit == "international foot")
    return 0.3048;
  if (unit == "us-ft" || unit == "us survey foot" || unit == "ftus") return 1200.0 / 3937.0;
  return 1.0;
}

// Ground distance in metres of one step (dx, dy) in CRS units at CRS point (x, y).
double groundStepMetres(OGRCoordinateTransformation* toGeographic, double x, double y, double dx,
                        double dy) {
  std::array<double, 2> xs{x, x + dx}, ys{y, y + dy};
  if (!toGeographic->Transform(2, xs.data(), ys.data())) return -1.0;
  constexpr double kDeg = 3.14159265358979323846 / 180.0;
  const double lat = 0.5 * (ys[0] + ys[1]) * kDeg;
  const double east = wgs84::eastWestMetres(lat, (xs[1] - xs[0]) * kDeg);
  const double north = wgs84::northSouthMetres(lat, (ys[1] - ys[0]) * kDeg);
  return std::hypot(east, north);
}

// Fills info.georef and the ground spacing from the dataset's CRS and geotransform. A
// georeferencing without meaning (pixels of no area, latitude 1000) is an error here rather
// than a blank image or a camera path through nowhere later.
Status computeGeoreference(GDALDataset& dataset, DemSourceInfo& grid) {
  const std::string& name = grid.name;
  std::array<double, 6> gt{};
  grid.georef.hasGeoTransform = dataset.GetGeoTransform(gt.data()) == CE_None;
  if (grid.georef.hasGeoTransform) grid.georef.geoTransform = gt;
  const OGRSpatialReference* srs = dataset.GetSpatialRef();
  OGRSpatialReference assumedWgs84;
  if (!srs && grid.georef.hasGeoTransform && gridLiesWithinGlobeDegrees(gt, grid.width, grid.height)) {
    // SRTM's BIL tiles come without a .prj: their pixel size is degrees, not metres.
    spdlog::warn("'{}' has no coordinate system; its grid lies within the globe's degrees, so it "
                 "is taken as WGS 84 latitude/longitude (gdal_edit.py -a_srs sets one)",
                 name);
    assumedWgs84.SetWellKnownGeogCS("WGS84");
    srs = &assumedWgs84;
  }
  if (srs) {
    char* wkt = nullptr;
    srs->exportToWkt(&wkt);
    grid.georef.crsWkt = wkt ? wkt : "";
    CPLFree(wkt);
    grid.georef.crsName = srs->GetName() ? srs->GetName() : "unnamed";
    grid.georef.isGeographic = srs->IsGeographic();
  }
  if (Status georef = checkGeoReference(grid.georef, grid.width, grid.height); !georef) {
    return makeError(
        "'{}' has an unusable georeferencing: {}; fix it (gdal_edit.py -unsetgt removes it, "
        "then --spacing METRES gives the sample spacing)",
        name, georef.error().message);
  }
  if (!grid.georef.hasGeoTransform) {
    spdlog::warn("'{}' has no georeferencing: assuming 1 m between samples (use --spacing)", name);
    grid.spacingXM = grid.spacingYM = 1.0;
    return {};
  }
  const double colDx = gt[1], colDy = gt[4], rowDx = gt[2], rowDy = gt[5];
  const double cx = gt[0] + 0.5 * grid.width * gt[1] + 0.5 * grid.height * gt[2];
  const double cy = gt[3] + 0.5 * grid.width * gt[4] + 0.5 * grid.height * gt[5];
  if (srs) {
    OGRSpatialReference wgs84;
    wgs84.SetWellKnownGeogCS("WGS84");
    wgs84.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
    OGRSpatialReference source(*srs);
    source.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
    std::unique_ptr<OGRCoordinateTransformation> toGeographic(
        OGRCreateCoordinateTransformation(&source, &wgs84));
    if (toGeographic) {
      const double sx = groundStepMetres(toGeographic.get(), cx, cy, colDx, colDy);
      const double sy = groundStepMetres(toGeographic.get(), cx, cy, rowDx, rowDy);
      if (sx > 0.0 && sy > 0.0) {
        grid.spacingXM = sx;
        grid.spacingYM = sy;
        return {};
      }
    }
    const double unit = srs->IsProjected() ? srs->GetLinearUnits() : 1.0;
    spdlog::warn("'{}': cannot convert its CRS to WGS84; using the pixel size in CRS units", name);
    grid.spacingXM = std::hypot(colDx, colDy) * unit;
    grid.spacingYM = std::hypot(rowDx, rowDy) * unit;
    return {};
  }
  spdlog::warn("'{}' has no CRS: taking its pixel size as metres", name);
  grid.spacingXM = std::hypot(colDx, colDy);
  grid.spacingYM = std::hypot(rowDx, rowDy);
  return {};
}

bool isIntegerType(GDALDataType type) {
  return type == GDT_Byte || type == GDT_UInt16 || type == GDT_Int16 || type == GDT_UInt32 ||
         type == GDT_Int32;
}

}  // namespace

struct DemSource::Impl {
  std::vector<gdal::DatasetPtr> inputs;
  gdal::DatasetPtr mosaic;
  GDALDataset* source = nullptr;  // inputs[0] or the mosaic
  HeightEncoding encoding = HeightEncoding::Plain;
  DemSourceInfo info;
  // Plain rasters: value -> metres and void test.
  bool hasNoData = false;
  double noData = 0.0;
  double scale = 1.0, offset = 0.0, toMetres = 1.0;
  // Set by fillVoids(), one or the other. `patches`: the filled heights of the voids, by sample
  // index (row * width + col), sorted, applied to every read (inputs that fit in memory and
  // are mostly data). `filled`: a void-free Float32 copy in metres that reads come from.
  std::vector<std::pair<std::uint64_t, float>> patches;
  bool patched = false;
  gdal::DatasetPtr filled;
  // fillVoidsOnRead(): each 256-sample block met so far that holds voids, by block index
  // (by * blocksX + bx), with its filled heights by sample index, sorted. `filledVoids`
  // counts the voids filled (on read so far, or by fillVoids()).
  bool fillOnRead = false;
  bool fillOnReadGaveUp = false;
  std::unordered_map<std::uint64_t, std::vector<std::pair<std::uint64_t, float>>> blockFills;
  std::size_t filledVoids = 0;
  // Holds the filled copy when it is on disk, and GDAL's work files; removed with everything
  // in it when the source is destroyed (after `filled`, declared after it, is closed).
  std::optional<ScratchFolder> scratch;
  std::vector<std::uint8_t> rgba;  // read buffer for encoded inputs

  // Reads the window of w x h samples at column x0, row y0 of the input as it is (voids NaN).
  Status readRaw(int x0, int y0, int w, int h, std::span<float> out);
  Status readPlain(int x0, int y0, int w, int h, std::span<float> out);
  Status readEncoded(int x0, int y0, int w, int h, std::span<float> out);
  // Fills the voids of 256-sample block (bx, by) from the input in a window reaching
  // kFillMargin samples beyond the block. Returns the block's voids with their filled
  // heights, by sample index, sorted; NaN where no data is within the window's reach.
  Result<std::vector<std::pair<std::uint64_t, float>>> fillBlock(int bx, int by);
  // fillVoidsOnRead(): replaces the voids in rows [firstRow, firstRow + rowCount) just read.
  Status fillVoidsInRows(int firstRow, int rowCount, std::span<float> heights);
  // The most voids filled block by block: a quarter of the samples, and at most 4 M.
  std::size_t maxLocallyFilledVoids() const {
    const std::size_t samples = std::size_t(info.width) * std::size_t(info.height);
    return std::min<std::size_t>(samples / 4, kMaxLocallyFilledVoids);
  }
};

DemSource::DemSource(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}

DemSource::~DemSource() {
  if (!impl_) return;
  impl_->filled.reset();  // closes the scratch copy before its folder goes
  impl_->scratch.reset();
}

const DemSourceInfo& DemSource::info() const {
  return impl_->info;
}

void DemSource::setReadCacheLimit(std::size_t bytes) {
  gdal::ensureRegistered();
  GDALSetCacheMax64(GIntBig(bytes));
}

Result<std::unique_ptr<DemSource>> DemSource::open(const std::vector<fs::path>& inputs,
                                                   const DemLoadOptions& options) {
  if (inputs.empty()) return makeError("no input DEM given");
  if (options.spacingM && !(*options.spacingM > 0.0 && std::isfinite(*options.spacingM))) {
    return makeError("--spacing must be a positive number of metres, got {}", *options.spacingM);
  }
  gdal::ensureRegistered();
  auto impl = std::make_unique<Impl>();
  for (const fs::path& path : inputs) {
    Result<gdal::DatasetPtr> dataset = openRaster(path);
    if (!dataset) return dataset.error();
    impl->inputs.push_back(std::move(dataset.value()));
  }
  DemSourceInfo& info = impl->info;
  info.name = inputs.size() == 1
                  ? inputs[0].string()
                  : fmt::format("mosaic of {} files from '{}'", inputs.size(), inputs[0].string());
  impl->source = impl->inputs[0].get();
  if (inputs.size() > 1) {
    Result<gdal::DatasetPtr> built = buildMosaic(impl->inputs, inputs);
    if (!built) return built.error();
    impl->mosaic = std::move(built.value());
    impl->source = impl->mosaic.get();
  }
  GDALDataset& source = *impl->source;
  info.width = source.GetRasterXSize();
  info.height = source.GetRasterYSize();
  if (info.width > kMaxGridSide || info.height > kMaxGridSide) {
    return makeError("'{}' is {} x {} samples; Tellus reads rasters of up to {} samples a side",
                     info.name, info.width, info.height, kMaxGridSide);
  }
  impl->encoding = options.encoding;
  GDALRasterBand* band = source.GetRasterBand(1);
  // GDAL reads whole blocks, and in a pixel-interleaved file a block holds every band: a
  // damaged file of a few hundred bytes can declare blocks of gigabytes (21505 bands of 63471
  // samples), which GDAL would allocate and clear before finding the data missing.
  int blockX = 0, blockY = 0;
  band->GetBlockSize(&blockX, &blockY);
  const double blockBytes = double(blockX) * double(blockY) *
                            double(GDALGetDataTypeSizeBytes(band->GetRasterDataType())) *
                            double(source.GetRasterCount());
  const std::string blocks = fmt::format("blocks of {} x {} samples in {} bands", blockX, blockY,
                                         source.GetRasterCount());
  if (blockBytes > kMaxBlockBytes) {
    return makeError(
        "'{}' has {} ({} each, more than any DEM needs): its layout is damaged or absurd; "
        "rewrite it with gdal_translate -b 1 -co TILED=YES",
        info.name, blocks, formatByteCount(blockBytes));
  }
  if (Status fits = checkMemoryFor(fmt::format("reading '{}' ({})", info.name, blocks),
                                   blockBytes, "rewrite it with gdal_translate -co TILED=YES");
      !fits) {
    return fits.error();
  }
  if (options.encoding == HeightEncoding::Plain) {
    if (band->GetRasterDataType() == GDT_Byte && source.GetRasterCount() >= 3) {
      return makeError(
          "'{}' is an 8-bit colour image, not a height raster; if it is an encoded "
          "elevation tile pass --encoding terrain-rgb or --encoding terrarium",
          info.name);
    }
    int hasNoData = 0, hasScale = 0, hasOffset = 0;
    impl->noData = band->GetNoDataValue(&hasNoData);
    impl->hasNoData = hasNoData != 0;
    const double scale = band->GetScale(&hasScale), offset = band->GetOffset(&hasOffset);
    impl->scale = hasScale ? scale : 1.0;
    impl->offset = hasOffset ? offset : 0.0;
    impl->toMetres = verticalUnitToMetres(band);
    if (isIntegerType(band->GetRasterDataType()) && impl->offset == 0.0) {
      info.heightStepM = std::abs(impl->scale) * impl->toMetres;
    }
  } else {
    const int bands = source.GetRasterCount();
    if (bands < 3) {
      return makeError("'{}' has {} band(s); --encoding {} needs an RGB image", info.name, bands,
                       heightEncodingName(options.encoding));
    }
    info.heightStepM = heightEncodingStepM(options.encoding);
  }
  if (Status georef = computeGeoreference(source, info); !georef) return georef.error();
  if (options.spacingM) info.spacingXM = info.spacingYM = *options.spacingM;
  if (Status spacing = checkSampleSpacing(info.spacingXM, info.spacingYM); !spacing) {
    return makeError("'{}': {}; give the right one with --spacing METRES", info.name,
                     spacing.error().message);
  }
  return std::unique_ptr<DemSource>(new DemSource(std::move(impl)));
}

Status DemSource::Impl::readRaw(int x0, int y0, int w, int h, std::span<float> out) {
  return encoding == HeightEncoding::Plain ? readPlain(x0, y0, w, h, out)
                                           : readEncoded(x0, y0, w, h, out);
}

Status DemSource::Impl::readPlain(int x0, int y0, int w, int h, std::span<float> out) {
  GDALRasterBand* band = source->GetRasterBand(1);
  if (band->RasterIO(GF_Read, x0, y0, w, h, out.data(), w, h, GDT_Float32, 0, 0) != CE_None) {
    return makeError("cannot read rows {}..{} of '{}': {}", y0, y0 + h - 1, info.name,
                     gdal::lastError());
  }
  const float noDataF = float(noData);
  const bool transform = scale != 1.0 || offset != 0.0 || toMetres != 1.0;
  for (float& v : out) {
    if (std::isnan(v) || (hasNoData && (v == noDataF || double(v) == noData))) {
      v = std::numeric_limits<float>::quiet_NaN();
      continue;
    }
    // The implausible test is on metres, after the file's scale and offset (which may be
    // anything, infinite or NaN included).
    const double metres = transform ? (double(v) * scale + offset) * toMetres : double(v);
    v = std::abs(metres) < kImplausibleHeightM ? float(metres)
                                                 : std::numeric_limits<float>::quiet_NaN();
  }
  return {};
}

Status DemSource::Impl::readEncoded(int x0, int y0, int w, int h, std::span<float> out) {
  const int bandCount = source->GetRasterCount() >= 4 ? 4 : 3;
  const std::size_t count = out.size();
  rgba.resize(count * std::size_t(bandCount));
  std::array<int, 4> bandMap{1, 2, 3, 4};
  if (source->RasterIO(GF_Read, x0, y0, w, h, rgba.data(), w, h, GDT_Byte, bandCount,
                       bandMap.data(), bandCount, GSpacing(bandCount) * w, 1,
                       nullptr) != CE_None) {
    return makeError("cannot read the colours of '{}': {}", info.name, gdal::lastError());
  }
  for (std::size_t i = 0; i < count; ++i) {
    const std::uint8_t* p = &rgba[i * std::size_t(bandCount)];
    if (bandCount == 4 && p[3] == 0) {
      out[i] = std::numeric_limits<float>::quiet_NaN();  // transparent = no data
      continue;
    }
    out[i] = float(encoding == HeightEncoding::TerrainRgb ? decodeTerrainRgb(p[0], p[1], p[2])
                                                          : decodeTerrarium(p[0], p[1], p[2]));
  }
  return {};
}

Status DemSource::readRows(int firstRow, int rowCount, std::span<float> heights) {
  Impl& d = *impl_;
  if (firstRow < 0 || rowCount < 1 || firstRow + rowCount > d.info.height ||
      heights.size() != std::size_t(d.info.width) * std::size_t(rowCount)) {
    return makeError("readRows({}, {}) outside the {} rows of '{}'", firstRow, rowCount,
                     d.info.height, d.info.name);
  }
  if (d.fillOnRead) {
    if (Status read = d.readRaw(0, firstRow, d.info.width, rowCount, heights); !read) return read;
    return d.fillVoidsInRows(firstRow, rowCount, heights);
  }
  if (d.patched) {
    if (Status read = d.readRaw(0, firstRow, d.info.width, rowCount, heights); !read) return read;
    const std::uint64_t first = std::uint64_t(firstRow) * std::uint64_t(d.info.width);
    const std::uint64_t end = first + heights.size();
    auto it = std::lower_bound(d.patches.begin(), d.patches.end(),
                               std::make_pair(first, -std::numeric_limits<float>::infinity()));
    for (; it != d.patches.end() && it->first < end; ++it) heights[it->first - first] = it->second;
    return {};
  }
  if (d.filled) {
    if (d.filled->GetRasterBand(1)->RasterIO(GF_Read, 0, firstRow, d.info.width, rowCount,
                                             heights.data(), d.info.width, rowCount, GDT_Float32, 0,
                                             0) != CE_None) {
      return makeError("cannot read the void-filled copy of '{}': {}", d.info.name,
                       gdal::lastError());
    }
    return {};
  }
  return d.readRaw(0, firstRow, d.info.width, rowCount, heights);
}

Result<DemStatistics> DemSource::scanStatistics(std::uint64_t maxSamplesRead) {
  const DemSourceInfo& info = impl_->info;
  const std::uint64_t samples = std::uint64_t(info.width) * std::uint64_t(info.height);
  DemStatistics stats;
  const std::uint64_t budget = std::max<std::uint64_t>(maxSamplesRead, 1);
  stats.rowStep = int(std::clamp<std::uint64_t>((samples + budget - 1) / budget, 1,
                                                std::uint64_t(std::max(1, info.height - 1))));
  const int rowsPerRead = stats.rowStep == 1 ? scanRows(info.width) : 1;
  std::vector<float> rows;
  float lo = std::numeric_limits<float>::max(), hi = std::numeric_limits<float>::lowest();
  Progress progress("scan", std::uint64_t(info.height));
  for (int row = 0; row < info.height; row += stats.rowStep * rowsPerRead) {
    const int count = std::min(rowsPerRead, info.height - row);
    rows.resize(std::size_t(info.width) * std::size_t(count));
    if (Status s = readRows(row, count, rows); !s) return s.error();
    for (float v : rows) {
      if (std::isnan(v)) {
        ++stats.voids;
        continue;
      }
      lo = std::min(lo, v);
      hi = std::max(hi, v);
    }
    stats.samplesRead += rows.size();
    progress.set(std::uint64_t(row + count));
  }
  if (lo <= hi) {
    stats.minM = lo;
    stats.maxM = hi;
    stats.hasValidSamples = true;
  }
  return stats;
}

Result<std::vector<std::pair<std::uint64_t, float>>> DemSource::Impl::fillBlock(int bx, int by) {
  const int width = info.width, height = info.height;
  const int x0 = std::max(0, bx * kFillBlock - kFillMargin);
  const int x1 = std::min(width, (bx + 1) * kFillBlock + kFillMargin);
  const int y0 = std::max(0, by * kFillBlock - kFillMargin);
  const int y1 = std::min(height, (by + 1) * kFillBlock + kFillMargin);
  const int w = x1 - x0, h = y1 - y0;
  std::vector<float> window(std::size_t(w) * std::size_t(h));
  if (Status s = readRaw(x0, y0, w, h, window); !s) return s.error();
  std::vector<std::uint8_t> valid(window.size());
  for (std::size_t i = 0; i < window.size(); ++i) valid[i] = std::isnan(window[i]) ? 0 : 255;
  // The block's own voids (the margin only lends its data), noted before the fill.
  const int bx0 = bx * kFillBlock, by0 = by * kFillBlock;
  const int bx1 = std::min(width, bx0 + kFillBlock), by1 = std::min(height, by0 + kFillBlock);
  std::vector<std::pair<int, int>> voids;  // (x, y) in the window
  for (int y = by0; y < by1; ++y) {
    for (int x = bx0; x < bx1; ++x) {
      if (!valid[std::size_t(y - y0) * std::size_t(w) + std::size_t(x - x0)]) {
        voids.emplace_back(x - x0, y - y0);
      }
    }
  }
  std::vector<std::pair<std::uint64_t, float>> filledHeights;
  if (voids.empty()) return filledHeights;
  if (std::none_of(valid.begin(), valid.end(), [](std::uint8_t v) { return v != 0; })) {
    // No data within reach: nothing to interpolate from.
    for (const auto& [x, y] : voids) {
      filledHeights.emplace_back(
          std::uint64_t(y0 + y) * std::uint64_t(width) + std::uint64_t(x0 + x),
          std::numeric_limits<float>::quiet_NaN());
    }
    return filledHeights;
  }
  GDALDriver* mem = GetGDALDriverManager()->GetDriverByName("MEM");
  gdal::DatasetPtr heights(mem->Create("", w, h, 1, GDT_Float32, nullptr));
  gdal::DatasetPtr mask(mem->Create("", w, h, 1, GDT_Byte, nullptr));
  if (!heights || !mask ||
      heights->GetRasterBand(1)->RasterIO(GF_Write, 0, 0, w, h, window.data(), w, h, GDT_Float32,
                                          0, 0) != CE_None ||
      mask->GetRasterBand(1)->RasterIO(GF_Write, 0, 0, w, h, valid.data(), w, h, GDT_Byte, 0,
                                       0) != CE_None) {
    return makeError("cannot set up the void filling of '{}': {}", info.name, gdal::lastError());
  }
  CPLStringList fillOptions;
  fillOptions.SetNameValue("TEMP_FILE_DRIVER", "MEM");
  if (GDALFillNodata(heights->GetRasterBand(1), mask->GetRasterBand(1), double(std::max(w, h)), 0,
                     0, fillOptions.List(), nullptr, nullptr) != CE_None ||
      heights->GetRasterBand(1)->RasterIO(GF_Read, 0, 0, w, h, window.data(), w, h, GDT_Float32, 0,
                                          0) != CE_None) {
    return makeError("cannot fill the voids of '{}': {}", info.name, gdal::lastError());
  }
  filledHeights.reserve(voids.size());
  for (const auto& [x, y] : voids) {
    filledHeights.emplace_back(std::uint64_t(y0 + y) * std::uint64_t(width) + std::uint64_t(x0 + x),
                               window[std::size_t(y) * std::size_t(w) + std::size_t(x)]);
  }
  return filledHeights;  // row by row within the block: sorted by sample index
}

Status DemSource::Impl::fillVoidsInRows(int firstRow, int rowCount, std::span<float> heights) {
  const int width = info.width;
  const std::uint64_t blocksX = std::uint64_t((width + kFillBlock - 1) / kFillBlock);
  for (int r = 0; r < rowCount; ++r) {
    float* row = heights.data() + std::size_t(r) * std::size_t(width);
    const int y = firstRow + r;
    for (int x = 0; x < width; ++x) {
      if (!std::isnan(row[x])) continue;
      const std::uint64_t key = std::uint64_t(y / kFillBlock) * blocksX + std::uint64_t(x / kFillBlock);
      auto block = blockFills.find(key);
      if (block == blockFills.end()) {
        Result<std::vector<std::pair<std::uint64_t, float>>> filledBlock =
            fillBlock(x / kFillBlock, y / kFillBlock);
        if (!filledBlock) return filledBlock.error();
        filledVoids += filledBlock->size();
        const bool outOfReach = std::any_of(filledBlock->begin(), filledBlock->end(),
                                            [](const auto& p) { return std::isnan(p.second); });
        if (outOfReach || filledVoids > maxLocallyFilledVoids()) {
          fillOnReadGaveUp = true;
          return makeError("'{}' has voids {} to fill block by block", info.name,
                           outOfReach ? "too large" : "too many");
        }
        block = blockFills.emplace(key, std::move(filledBlock.value())).first;
      }
      const std::uint64_t index = std::uint64_t(y) * std::uint64_t(width) + std::uint64_t(x);
      const auto it = std::lower_bound(block->second.begin(), block->second.end(),
                                       std::make_pair(index, -std::numeric_limits<float>::infinity()));
      row[x] = it->second;  // every void of the block is in its fill
    }
  }
  return {};
}

void DemSource::fillVoidsOnRead() {
  Impl& d = *impl_;
  if (d.filled || d.patched) return;
  d.fillOnRead = true;
  d.fillOnReadGaveUp = false;
  d.blockFills.clear();
  d.filledVoids = 0;
}

bool DemSource::voidFillingOnReadGaveUp() const {
  return impl_->fillOnReadGaveUp;
}

std::size_t DemSource::filledVoidCount() const {
  return impl_->filledVoids;
}

Status DemSource::fillVoidsLocally(const std::vector<std::uint64_t>& voidIndices,
                                   float lowestValid) {
  Impl& d = *impl_;
  const int width = d.info.width;
  std::vector<std::pair<int, int>> blocks;  // (by, bx), in row order
  for (const std::uint64_t index : voidIndices) {
    blocks.emplace_back(int(index / std::uint64_t(width)) / kFillBlock,
                        int(index % std::uint64_t(width)) / kFillBlock);
  }
  std::sort(blocks.begin(), blocks.end());
  blocks.erase(std::unique(blocks.begin(), blocks.end()), blocks.end());
  std::vector<std::pair<std::uint64_t, float>> patches;
  patches.reserve(voidIndices.size());
  Progress progress("fill voids", blocks.size());
  for (const auto& [by, bx] : blocks) {
    Result<std::vector<std::pair<std::uint64_t, float>>> filledBlock = d.fillBlock(bx, by);
    if (!filledBlock) return filledBlock.error();
    for (auto [index, height] : filledBlock.value()) {
      // Out of reach of any data in the window: the lowest valid height.
      patches.emplace_back(index, std::isnan(height) ? lowestValid : height);
    }
    progress.advance();
  }
  std::sort(patches.begin(), patches.end());
  d.patches = std::move(patches);
  d.patched = true;
  return {};
}

Result<std::size_t> DemSource::fillVoids(const fs::path& scratchFolder,
                                         std::size_t inMemorySamples) {
  Impl& d = *impl_;
  if (d.filled || d.patched) return d.filledVoids;
  d.fillOnRead = false;  // a scan first, then one way of filling for every read
  d.fillOnReadGaveUp = false;
  d.blockFills.clear();
  d.filledVoids = 0;
  const int width = d.info.width, height = d.info.height;
  const std::size_t samples = std::size_t(width) * std::size_t(height);
  // Pass 1: count the voids, and note where they are while they are few.
  std::size_t voids = 0;
  std::vector<float> rows;
  std::vector<std::uint64_t> voidIndices;
  const std::size_t maxLocalVoids = d.maxLocallyFilledVoids();
  float lowestSeen = std::numeric_limits<float>::max();
  {
    Progress progress("scan", std::uint64_t(height));
    for (int row = 0; row < height; row += scanRows(width)) {
      const int count = std::min(scanRows(width), height - row);
      rows.resize(std::size_t(width) * std::size_t(count));
      if (Status s = readRows(row, count, rows); !s) return s.error();
      for (std::size_t i = 0; i < rows.size(); ++i) {
        if (!std::isnan(rows[i])) {
          lowestSeen = std::min(lowestSeen, rows[i]);
          continue;
        }
        ++voids;
        if (voidIndices.size() <= maxLocalVoids) {
          voidIndices.push_back(std::uint64_t(row) * std::uint64_t(width) + i);
        }
      }
      progress.advance(std::uint64_t(count));
    }
  }
  if (voids == 0) return voids;
  if (voids == samples) return makeError("'{}' has no valid samples (all void)", d.info.name);
  d.filledVoids = voids;
  if (samples <= inMemorySamples && voids <= maxLocalVoids) {
    if (Status s = fillVoidsLocally(voidIndices, lowestSeen); !s) return s.error();
    return voids;
  }

  // Pass 2: copy heights and a validity mask into a scratch dataset, then fill it. On disk,
  // everything (the copy, the mask, GDAL's own work files) lives in a private scratch folder
  // inside `scratchFolder`, never in the current directory.
  const bool inMemory = samples <= inMemorySamples;
  GDALDriver* driver = GetGDALDriverManager()->GetDriverByName(inMemory ? "MEM" : "GTiff");
  fs::path file, maskFile;
  char** createOptions = nullptr;
  if (!inMemory) {
    Result<ScratchFolder> scratch = ScratchFolder::create(scratchFolder);
    if (!scratch) return scratch.error();
    d.scratch.emplace(std::move(scratch.value()));
    file = d.scratch->path() / "filled.tif";
    maskFile = d.scratch->path() / "mask.tif";
    createOptions = CSLSetNameValue(createOptions, "TILED", "YES");
    createOptions = CSLSetNameValue(createOptions, "BIGTIFF", "IF_SAFER");
  }
  gdal::DatasetPtr heights(
      driver->Create(file.c_str(), width, height, 1, GDT_Float32, createOptions));
  gdal::DatasetPtr mask(
      driver->Create(maskFile.c_str(), width, height, 1, GDT_Byte, createOptions));
  CSLDestroy(createOptions);
  auto cleanup = [&] {
    mask.reset();
    std::error_code ec;
    if (!maskFile.empty()) fs::remove(maskFile, ec);
  };
  if (!heights || !mask) {
    cleanup();
    heights.reset();
    d.scratch.reset();
    return makeError("cannot create a scratch copy to fill the voids of '{}': {}", d.info.name,
                     gdal::lastError());
  }
  std::vector<std::uint8_t> valid;
  float lowest = std::numeric_limits<float>::max();
  for (int row = 0; row < height; row += scanRows(width)) {
    const int count = std::min(scanRows(width), height - row);
    rows.resize(std::size_t(width) * std::size_t(count));
    if (Status s = readRows(row, count, rows); !s) {
      cleanup();
      return s.error();
    }
    valid.resize(rows.size());
    for (std::size_t i = 0; i < rows.size(); ++i) {
      valid[i] = std::isnan(rows[i]) ? 0 : 255;
      if (valid[i]) lowest = std::min(lowest, rows[i]);
    }
    if (heights->GetRasterBand(1)->RasterIO(GF_Write, 0, row, width, count, rows.data(), width,
                                            count, GDT_Float32, 0, 0) != CE_None ||
        mask->GetRasterBand(1)->RasterIO(GF_Write, 0, row, width, count, valid.data(), width, count,
                                         GDT_Byte, 0, 0) != CE_None) {
      cleanup();
      return makeError("cannot write the scratch copy of '{}': {}", d.info.name, gdal::lastError());
    }
  }
  const double searchDistance = double(std::max(width, height));
  {
    Progress progress("fill voids", 1000);
    // GDAL's work files: in memory too, or in the scratch folder (GDAL puts them in
    // CPL_TMPDIR, by default the current directory).
    CPLStringList fillOptions;
    fillOptions.SetNameValue("TEMP_FILE_DRIVER", inMemory ? "MEM" : "GTiff");
    const std::string workFolder = inMemory ? std::string() : d.scratch->path().string();
    CPLSetThreadLocalConfigOption("CPL_TMPDIR", inMemory ? nullptr : workFolder.c_str());
    const CPLErr filledOk =
        GDALFillNodata(heights->GetRasterBand(1), mask->GetRasterBand(1), searchDistance, 0, 0,
                       fillOptions.List(), reportProgress, &progress);
    CPLSetThreadLocalConfigOption("CPL_TMPDIR", nullptr);
    if (filledOk != CE_None) {
      cleanup();
      return makeError("cannot fill the voids of '{}': {}", d.info.name, gdal::lastError());
    }
  }
  cleanup();
  // Anything GDAL left (voids out of reach) takes the lowest valid height.
  d.filled = std::move(heights);
  for (int row = 0; row < height; row += scanRows(width)) {
    const int count = std::min(scanRows(width), height - row);
    rows.resize(std::size_t(width) * std::size_t(count));
    if (Status s = readRows(row, count, rows); !s) return s.error();
    bool changed = false;
    for (float& v : rows) {
      if (std::isnan(v)) {
        v = lowest;
        changed = true;
      }
    }
    if (changed &&
        d.filled->GetRasterBand(1)->RasterIO(GF_Write, 0, row, width, count, rows.data(), width,
                                             count, GDT_Float32, 0, 0) != CE_None) {
      return makeError("cannot write the scratch copy of '{}': {}", d.info.name, gdal::lastError());
    }
  }
  return voids;
}

}  // namespace tellus
