#include "tellus/dem/dem_loader.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include <gdal_alg.h>
#include <gdal_utils.h>
#include <ogr_spatialref.h>
#include <spdlog/spdlog.h>

#include "tellus/core/geodesy.hpp"
#include "tellus/core/progress.hpp"
#include "tellus/dem/gdal_support.hpp"

namespace tellus {
namespace fs = std::filesystem;

namespace {

constexpr double kImplausibleHeightM = 1e6;  // |h| at or above this is treated as a void
constexpr std::uint64_t kProgressSteps = 1000;

// GDAL progress callback feeding a Progress of kProgressSteps steps.
int CPL_STDCALL reportProgress(double complete, const char*, void* progress) {
  static_cast<Progress*>(progress)->set(std::uint64_t(complete * double(kProgressSteps)));
  return TRUE;
}

GDALRasterIOExtraArg progressArgument(Progress& progress) {
  GDALRasterIOExtraArg extra;
  INIT_RASTERIO_EXTRA_ARG(extra);
  extra.pfnProgress = reportProgress;
  extra.pProgressData = &progress;
  return extra;
}

// Heights read from the raster, NaN marking voids.
struct RawHeights {
  int width = 0;
  int height = 0;
  std::vector<float> values;
};

Result<gdal::DatasetPtr> openRaster(const fs::path& path) {
  std::error_code ec;
  if (!fs::exists(path, ec)) return makeError("cannot open '{}': no such file", path.string());
  if (fs::is_directory(path, ec))
    return makeError("cannot open '{}': it is a folder", path.string());
  gdal::DatasetPtr dataset(GDALDataset::FromHandle(
      GDALOpenEx(path.c_str(), GDAL_OF_RASTER | GDAL_OF_READONLY, nullptr, nullptr, nullptr)));
  if (!dataset) {
    return makeError("cannot read '{}' as a raster: {}", path.string(), gdal::lastError());
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

Result<RawHeights> readPlainHeights(GDALDataset& dataset, const std::string& name) {
  GDALRasterBand* band = dataset.GetRasterBand(1);
  if (band->GetRasterDataType() == GDT_Byte && dataset.GetRasterCount() >= 3) {
    return makeError(
        "'{}' is an 8-bit colour image, not a height raster; if it is an encoded "
        "elevation tile pass --encoding terrain-rgb or --encoding terrarium",
        name);
  }
  RawHeights raw{dataset.GetRasterXSize(), dataset.GetRasterYSize(), {}};
  raw.values.resize(size_t(raw.width) * size_t(raw.height));
  Progress progress("read", kProgressSteps);
  GDALRasterIOExtraArg extra = progressArgument(progress);
  if (band->RasterIO(GF_Read, 0, 0, raw.width, raw.height, raw.values.data(), raw.width, raw.height,
                     GDT_Float32, 0, 0, &extra) != CE_None) {
    return makeError("cannot read the samples of '{}': {}", name, gdal::lastError());
  }
  int hasNoData = 0;
  const double noData = band->GetNoDataValue(&hasNoData);
  const float noDataF = float(noData);
  int hasScale = 0, hasOffset = 0;
  const double scale = band->GetScale(&hasScale), offset = band->GetOffset(&hasOffset);
  const double toMetres = verticalUnitToMetres(band);
  const bool transform =
      (hasScale && scale != 1.0) || (hasOffset && offset != 0.0) || toMetres != 1.0;
  for (float& v : raw.values) {
    const bool isVoid = std::isnan(v) || (hasNoData && (v == noDataF || double(v) == noData)) ||
                        std::abs(v) >= kImplausibleHeightM;
    if (isVoid) {
      v = std::numeric_limits<float>::quiet_NaN();
    } else if (transform) {
      v = float((double(v) * (hasScale ? scale : 1.0) + (hasOffset ? offset : 0.0)) * toMetres);
    }
  }
  return raw;
}

Result<RawHeights> readEncodedHeights(GDALDataset& dataset, HeightEncoding encoding,
                                      const std::string& name) {
  const int bands = dataset.GetRasterCount();
  if (bands < 3) {
    return makeError("'{}' has {} band(s); --encoding {} needs an RGB image", name, bands,
                     heightEncodingName(encoding));
  }
  RawHeights raw{dataset.GetRasterXSize(), dataset.GetRasterYSize(), {}};
  const size_t count = size_t(raw.width) * size_t(raw.height);
  const int bandCount = bands >= 4 ? 4 : 3;
  std::vector<std::uint8_t> rgba(count * size_t(bandCount));
  std::array<int, 4> bandMap{1, 2, 3, 4};
  // Pixel-interleaved read: RGB(A) per sample.
  Progress progress("read", kProgressSteps);
  GDALRasterIOExtraArg extra = progressArgument(progress);
  if (dataset.RasterIO(GF_Read, 0, 0, raw.width, raw.height, rgba.data(), raw.width, raw.height,
                       GDT_Byte, bandCount, bandMap.data(), bandCount,
                       GSpacing(bandCount) * raw.width, 1, &extra) != CE_None) {
    return makeError("cannot read the colours of '{}': {}", name, gdal::lastError());
  }
  raw.values.resize(count);
  for (size_t i = 0; i < count; ++i) {
    const std::uint8_t* p = &rgba[i * size_t(bandCount)];
    if (bandCount == 4 && p[3] == 0) {
      raw.values[i] = std::numeric_limits<float>::quiet_NaN();  // transparent = no data
      continue;
    }
    raw.values[i] =
        float(encoding == HeightEncoding::TerrainRgb ? decodeTerrainRgb(p[0], p[1], p[2])
                                                     : decodeTerrarium(p[0], p[1], p[2]));
  }
  return raw;
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

// Fills grid.georef and the ground spacing from the dataset's CRS and geotransform.
void computeGeoreference(GDALDataset& dataset, const std::string& name, HeightGrid& grid) {
  std::array<double, 6> gt{};
  grid.georef.hasGeoTransform = dataset.GetGeoTransform(gt.data()) == CE_None;
  if (grid.georef.hasGeoTransform) grid.georef.geoTransform = gt;
  const OGRSpatialReference* srs = dataset.GetSpatialRef();
  if (srs) {
    char* wkt = nullptr;
    srs->exportToWkt(&wkt);
    grid.georef.crsWkt = wkt ? wkt : "";
    CPLFree(wkt);
    grid.georef.crsName = srs->GetName() ? srs->GetName() : "unnamed";
    grid.georef.isGeographic = srs->IsGeographic();
  }
  if (!grid.georef.hasGeoTransform) {
    spdlog::warn("'{}' has no georeferencing: assuming 1 m between samples (use --spacing)", name);
    grid.spacingXM = grid.spacingYM = 1.0;
    return;
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
        return;
      }
    }
    const double unit = srs->IsProjected() ? srs->GetLinearUnits() : 1.0;
    spdlog::warn("'{}': cannot convert its CRS to WGS84; using the pixel size in CRS units", name);
    grid.spacingXM = std::hypot(colDx, colDy) * unit;
    grid.spacingYM = std::hypot(rowDx, rowDy) * unit;
    return;
  }
  spdlog::warn("'{}' has no CRS: taking its pixel size as metres", name);
  grid.spacingXM = std::hypot(colDx, colDy);
  grid.spacingYM = std::hypot(rowDx, rowDy);
}

// Replaces NaN samples by inverse-distance interpolation (GDALFillNodata). Returns how many
// samples were void.
Result<size_t> fillVoids(RawHeights& raw, const std::string& name) {
  const size_t voids = size_t(
      std::count_if(raw.values.begin(), raw.values.end(), [](float v) { return std::isnan(v); }));
  if (voids == 0) return voids;
  if (voids == raw.values.size()) return makeError("'{}' has no valid samples (all void)", name);
  GDALDriver* mem = GetGDALDriverManager()->GetDriverByName("MEM");
  gdal::DatasetPtr heights(mem->Create("", raw.width, raw.height, 1, GDT_Float32, nullptr));
  gdal::DatasetPtr mask(mem->Create("", raw.width, raw.height, 1, GDT_Byte, nullptr));
  if (!heights || !mask) return makeError("cannot fill the voids of '{}': out of memory", name);
  std::vector<std::uint8_t> valid(raw.values.size());
  std::transform(raw.values.begin(), raw.values.end(), valid.begin(),
                 [](float v) { return std::uint8_t(std::isnan(v) ? 0 : 255); });
  bool ok =
      heights->GetRasterBand(1)->RasterIO(GF_Write, 0, 0, raw.width, raw.height, raw.values.data(),
                                          raw.width, raw.height, GDT_Float32, 0, 0) == CE_None &&
      mask->GetRasterBand(1)->RasterIO(GF_Write, 0, 0, raw.width, raw.height, valid.data(),
                                       raw.width, raw.height, GDT_Byte, 0, 0) == CE_None;
  const double searchDistance = double(std::max(raw.width, raw.height));
  Progress progress("fill voids", kProgressSteps);
  ok = ok && GDALFillNodata(heights->GetRasterBand(1), mask->GetRasterBand(1), searchDistance, 0, 0,
                            nullptr, reportProgress, &progress) == CE_None;
  ok = ok &&
       heights->GetRasterBand(1)->RasterIO(GF_Read, 0, 0, raw.width, raw.height, raw.values.data(),
                                           raw.width, raw.height, GDT_Float32, 0, 0) == CE_None;
  if (!ok) return makeError("cannot fill the voids of '{}': {}", name, gdal::lastError());
  // Anything GDAL left (unreachable voids) takes the lowest valid height.
  float lowest = std::numeric_limits<float>::max();
  for (size_t i = 0; i < valid.size(); ++i) {
    if (valid[i]) lowest = std::min(lowest, raw.values[i]);
  }
  for (float& v : raw.values) {
    if (std::isnan(v)) v = lowest;
  }
  return voids;
}

}  // namespace

Result<HeightGrid> loadDem(const std::vector<fs::path>& inputs, const DemLoadOptions& options) {
  if (inputs.empty()) return makeError("no input DEM given");
  if (options.spacingM && !(*options.spacingM > 0.0 && std::isfinite(*options.spacingM))) {
    return makeError("--spacing must be a positive number of metres, got {}", *options.spacingM);
  }
  gdal::ensureRegistered();

  std::vector<gdal::DatasetPtr> datasets;
  for (const fs::path& path : inputs) {
    Result<gdal::DatasetPtr> dataset = openRaster(path);
    if (!dataset) return dataset.error();
    datasets.push_back(std::move(dataset.value()));
  }
  const std::string name = inputs.size() == 1 ? inputs[0].string()
                                              : fmt::format("mosaic of {} files from '{}'",
                                                            inputs.size(), inputs[0].string());
  gdal::DatasetPtr mosaic;
  GDALDataset* source = datasets[0].get();
  if (inputs.size() > 1) {
    Result<gdal::DatasetPtr> built = buildMosaic(datasets, inputs);
    if (!built) return built.error();
    mosaic = std::move(built.value());
    source = mosaic.get();
  }

  Result<RawHeights> raw = options.encoding == HeightEncoding::Plain
                               ? readPlainHeights(*source, name)
                               : readEncodedHeights(*source, options.encoding, name);
  if (!raw) return raw.error();
  Result<size_t> voids = fillVoids(raw.value(), name);
  if (!voids) return voids.error();

  HeightGrid grid;
  grid.width = raw->width;
  grid.height = raw->height;
  grid.heights = std::move(raw->values);
  grid.filledVoidCount = voids.value();
  computeGeoreference(*source, name, grid);
  if (options.spacingM) grid.spacingXM = grid.spacingYM = *options.spacingM;
  return grid;
}

}  // namespace tellus
