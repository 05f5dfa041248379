#include "tellus/dem/imagery_pyramid.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <functional>
#include <vector>

#include <gdal_alg.h>
#include <gdal_utils.h>
#include <ogr_spatialref.h>
#include <spdlog/spdlog.h>
#include <unistd.h>

#include "tellus/core/atomic_output.hpp"
#include "tellus/core/progress.hpp"
#include "tellus/core/geotransform_check.hpp"
#include "tellus/dem/gdal_support.hpp"

namespace tellus {
namespace {

constexpr char kMagic[8] = {'T', 'L', 'S', 'I', 'M', 'G', '0', '1'};
constexpr std::uint32_t kVersion = 1;
constexpr std::size_t kHeaderBytes = 4096;
constexpr std::size_t kWktOffset = 96;
constexpr std::size_t kMaxWktBytes = kHeaderBytes - kWktOffset;

int halved(int size, int times) { return int((std::int64_t(size) + (std::int64_t(1) << times) - 1) >> times); }

int levelsFor(int width, int height, int tileSize) {
  int levels = 1;
  while (std::max(halved(width, levels - 1), halved(height, levels - 1)) > tileSize) ++levels;
  return levels;
}

template <typename T>
void put(std::vector<std::byte>& header, std::size_t offset, T value) {
  std::memcpy(header.data() + offset, &value, sizeof(T));
}
template <typename T>
T get(std::span<const std::byte> header, std::size_t offset) {
  T value;
  std::memcpy(&value, header.data() + offset, sizeof(T));
  return value;
}

std::int64_t modifiedNs(const std::filesystem::path& path) {
  std::error_code ec;
  const auto time = std::filesystem::last_write_time(path, ec);
  return ec ? 0 : std::int64_t(std::chrono::duration_cast<std::chrono::nanoseconds>(
                                   time.time_since_epoch()).count());
}

// The next level of a premultiplied RGBA8 level: each texel the mean of the (up to) four below
// it, texels beyond the image counting as transparent.
std::vector<std::uint8_t> halveLevel(const std::vector<std::uint8_t>& rgba, int width, int height) {
  const int w = halved(width, 1), h = halved(height, 1);
  std::vector<std::uint8_t> out(std::size_t(w) * h * 4);
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      unsigned sum[4] = {0, 0, 0, 0};
      for (int dy = 0; dy < 2; ++dy) {
        for (int dx = 0; dx < 2; ++dx) {
          const int sx = 2 * x + dx, sy = 2 * y + dy;
          if (sx >= width || sy >= height) continue;
          const std::uint8_t* t = &rgba[(std::size_t(sy) * width + sx) * 4];
          for (int c = 0; c < 4; ++c) sum[c] += t[c];
        }
      }
      std::uint8_t* o = &out[(std::size_t(y) * w + x) * 4];
      for (int c = 0; c < 4; ++c) o[c] = std::uint8_t((sum[c] + 2) / 4);
    }
  }
  return out;
}

// Writes `level`'s tiles (row by row) to `file`, zero beyond the level's texels.
bool writeLevelTiles(std::FILE* file, const std::vector<std::uint8_t>& rgba, int width, int height,
                     int tileSize) {
  const int tilesX = (width + tileSize - 1) / tileSize, tilesY = (height + tileSize - 1) / tileSize;
  std::vector<std::uint8_t> tile(std::size_t(tileSize) * tileSize * 4);
  for (int ty = 0; ty < tilesY; ++ty) {
    for (int tx = 0; tx < tilesX; ++tx) {
      std::fill(tile.begin(), tile.end(), std::uint8_t(0));
      const int x0 = tx * tileSize, y0 = ty * tileSize;
      const int w = std::min(tileSize, width - x0), h = std::min(tileSize, height - y0);
      for (int row = 0; row < h; ++row) {
        std::memcpy(&tile[std::size_t(row) * tileSize * 4],
                    &rgba[(std::size_t(y0 + row) * width + x0) * 4], std::size_t(w) * 4);
      }
      if (std::fwrite(tile.data(), 1, tile.size(), file) != tile.size()) return false;
    }
  }
  return true;
}

// The source's CRS as WKT; a source without one must be a grid within the globe's degrees
// (a JPEG with a world file: latitude/longitude), given as WGS 84.
Result<std::string> sourceCrsWkt(GDALDataset& dataset, const std::string& name) {
  if (const OGRSpatialReference* srs = dataset.GetSpatialRef()) {
    char* text = nullptr;
    srs->exportToWkt(&text);
    std::string wkt = text ? text : "";
    CPLFree(text);
    return wkt;
  }
  double gt[6] = {};
  dataset.GetGeoTransform(gt);
  const double slack = 1e-6 * 360.0;
  if (gt[0] < -180.0 - slack || gt[0] + dataset.GetRasterXSize() * gt[1] > 180.0 + slack ||
      gt[3] > 90.0 + slack || gt[3] + dataset.GetRasterYSize() * gt[5] < -90.0 - slack) {
    return makeError("imagery '{}' has no CRS and its grid is not within the globe's degrees", name);
  }
  return gdal::wgs84Wkt();
}

struct WarpedDatasetCloser {
  void operator()(GDALDatasetH dataset) const { GDALClose(dataset); }
};

// `source` resampled onto `grid` (bilinear; a fourth band, alpha, says where the source was):
// a virtual dataset that reads `source` as its rows are asked for.
Result<gdal::DatasetPtr> warpedOnto(GDALDataset& source, const ImageryWarpGrid& grid,
                                    const std::string& name) {
  Result<std::string> sourceWkt = sourceCrsWkt(source, name);
  if (!sourceWkt) return sourceWkt.error();
  const auto& g = grid.geoTransform;
  const double minX = g[0], maxX = g[0] + grid.width * g[1];
  const double maxY = g[3], minY = g[3] + grid.height * g[5];
  const std::vector<std::string> args = {
      "-of", "VRT", "-s_srs", *sourceWkt, "-t_srs", grid.crsWkt,
      "-te", fmt::format("{:.17g}", minX), fmt::format("{:.17g}", minY),
      fmt::format("{:.17g}", maxX), fmt::format("{:.17g}", maxY),
      "-ts", std::to_string(grid.width), std::to_string(grid.height),
      "-r", "bilinear", "-dstalpha", "-q"};
  char** argv = nullptr;
  for (const std::string& a : args) argv = CSLAddString(argv, a.c_str());
  GDALWarpAppOptions* options = GDALWarpAppOptionsNew(argv, nullptr);
  CSLDestroy(argv);
  if (!options) return makeError("imagery '{}': cannot set up the warp: {}", name, gdal::lastError());
  GDALDatasetH input = GDALDataset::ToHandle(&source);
  int usageError = 0;
  GDALDatasetH warped = GDALWarp("", nullptr, 1, &input, options, &usageError);
  GDALWarpAppOptionsFree(options);
  if (!warped) return makeError("imagery '{}': cannot warp it onto the store's grid: {}", name, gdal::lastError());
  return gdal::DatasetPtr(GDALDataset::FromHandle(warped));
}

}  // namespace

Result<ImageryWarpGrid> imageryGridOnGlobe(const std::filesystem::path& source, int maxSide) {
  // The globe as a latitude/longitude grid finer than any source (2^24 columns: 2.4 m).
  GeoReference globe;
  globe.crsWkt = gdal::wgs84Wkt();
  globe.crsName = "WGS 84";
  globe.hasGeoTransform = true;
  globe.isGeographic = true;
  constexpr int kColumns = 1 << 24, kRows = 1 << 23;
  globe.geoTransform = {-180.0, 360.0 / kColumns, 0.0, 90.0, 0.0, -180.0 / kRows};
  return imageryGridOnStore(source, globe, kColumns, kRows, maxSide);
}

Result<ImageryWarpGrid> imageryGridOnStore(const std::filesystem::path& source,
                                          const GeoReference& storeGeoref, int dataWidth,
                                          int dataHeight, int maxSide) {
  gdal::ensureRegistered();
  const std::string name = source.string();
  if (storeGeoref.crsWkt.empty() || !storeGeoref.hasGeoTransform) {
    return makeError("imagery '{}': the store has no georeferencing, so imagery cannot be placed on it", name);
  }
  const auto& s = storeGeoref.geoTransform;
  if (s[2] != 0.0 || s[4] != 0.0 || s[1] <= 0.0 || s[5] >= 0.0) {
    return makeError("imagery '{}': the store's grid is not north-up", name);
  }
  Result<gdal::DatasetPtr> opened = gdal::openRasterFile(
      source, "imagery", "a georeferenced RGB image (a GeoTIFF, or a JPEG or PNG with a world file)");
  if (!opened) return opened.error();
  GDALDataset& dataset = *opened.value();
  double sourceGt[6] = {};
  if (dataset.GetGeoTransform(sourceGt) != CE_None) {
    return makeError("imagery '{}' has no georeferencing (a GeoTIFF or a world file)", name);
  }
  Result<std::string> sourceWkt = sourceCrsWkt(dataset, name);
  if (!sourceWkt) return sourceWkt.error();
  // GDAL's suggestion: the source's footprint and resolution in the store's CRS.
  char** transformerOptions = nullptr;
  transformerOptions = CSLSetNameValue(transformerOptions, "SRC_SRS", sourceWkt->c_str());
  transformerOptions = CSLSetNameValue(transformerOptions, "DST_SRS", storeGeoref.crsWkt.c_str());
  void* transformer =
      GDALCreateGenImgProjTransformer2(GDALDataset::ToHandle(&dataset), nullptr, transformerOptions);
  CSLDestroy(transformerOptions);
  if (!transformer) {
    return makeError("imagery '{}': no transformation from its CRS to the store's: {}", name, gdal::lastError());
  }
  double suggested[6] = {};
  double extent[4] = {};  // min x, min y, max x, max y
  int suggestedW = 0, suggestedH = 0;
  const CPLErr suggestion = GDALSuggestedWarpOutput2(GDALDataset::ToHandle(&dataset), GDALGenImgProjTransform,
                                                     transformer, suggested, &suggestedW, &suggestedH, extent, 0);
  GDALDestroyGenImgProjTransformer(transformer);
  if (suggestion != CE_None || suggested[1] <= 0.0 || suggested[5] >= 0.0) {
    return makeError("imagery '{}': its footprint in the store's CRS cannot be computed: {}", name, gdal::lastError());
  }
  double rx = suggested[1], ry = -suggested[5];
  const double storeW = dataWidth * s[1], storeH = dataHeight * -s[5];
  for (;;) {
    const auto clampTo = [](double v, double hi) { return std::clamp(v, 0.0, hi); };
    const double columns = std::ceil(storeW / rx - 1e-9), rows = std::ceil(storeH / ry - 1e-9);
    const double i0 = clampTo(std::floor((extent[0] - s[0]) / rx), columns);
    const double i1 = clampTo(std::ceil((extent[2] - s[0]) / rx), columns);
    const double j0 = clampTo(std::floor((s[3] - extent[3]) / ry), rows);
    const double j1 = clampTo(std::ceil((s[3] - extent[1]) / ry), rows);
    if (i1 <= i0 || j1 <= j0) {
      return makeError("imagery '{}' does not overlap the store", name);
    }
    const double side = std::max(i1 - i0, j1 - j0);
    if (side > maxSide) {
      const double coarser = side / maxSide * (1.0 + 1e-9);
      rx *= coarser;
      ry *= coarser;
      continue;
    }
    ImageryWarpGrid grid;
    grid.crsWkt = storeGeoref.crsWkt;
    grid.geoTransform = {s[0] + i0 * rx, rx, 0.0, s[3] - j0 * ry, 0.0, -ry};
    grid.width = int(i1 - i0);
    grid.height = int(j1 - j0);
    return grid;
  }
}

namespace {

}  // namespace

struct ImageryPyramid::Transform {
  std::unique_ptr<OGRCoordinateTransformation> toLatLon;  // null: the grid is latitude/longitude
};

ImageryPyramid::ImageryPyramid() = default;
ImageryPyramid::~ImageryPyramid() = default;
ImageryPyramid::ImageryPyramid(ImageryPyramid&&) noexcept = default;
ImageryPyramid& ImageryPyramid::operator=(ImageryPyramid&&) noexcept = default;

namespace {

// The transformation from `wkt` (empty: latitude/longitude already) to WGS 84 lon/lat.
Result<std::unique_ptr<OGRCoordinateTransformation>> latLonTransformFrom(const std::string& wkt,
                                                                         const std::string& name) {
  if (wkt.empty()) return std::unique_ptr<OGRCoordinateTransformation>();
  OGRSpatialReference source, wgs84;
  if (source.importFromWkt(wkt.c_str()) != OGRERR_NONE) {
    return makeError("imagery '{}': its CRS cannot be read", name);
  }
  source.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
  wgs84.SetWellKnownGeogCS("WGS84");
  wgs84.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
  std::unique_ptr<OGRCoordinateTransformation> t(OGRCreateCoordinateTransformation(&source, &wgs84));
  if (!t) return makeError("imagery '{}': no transformation from its CRS to latitude/longitude", name);
  return t;
}

}  // namespace

Status buildImageryPyramid(const std::filesystem::path& source, const std::filesystem::path& output,
                           const ImageryBuildOptions& options) {
  gdal::ensureRegistered();
  const std::string name = source.string();
  const int tileSize = options.tileSize;
  if (tileSize < 16 || tileSize > 2048 || !std::has_single_bit(unsigned(tileSize))) {
    return makeError("imagery tiles must be a power of two from 16 to 2048 texels, got {}", tileSize);
  }
  Result<gdal::DatasetPtr> opened = gdal::openRasterFile(
      source, "imagery", "a georeferenced RGB image (a GeoTIFF, or a JPEG or PNG with a world file)");
  if (!opened) return opened.error();
  gdal::DatasetPtr dataset = std::move(opened.value());
  gdal::DatasetPtr original;  // the source, kept open under its warped view
  if (options.warp) {
    Result<gdal::DatasetPtr> warped = warpedOnto(*dataset, *options.warp, name);
    if (!warped) return warped.error();
    original = std::move(dataset);
    dataset = std::move(warped.value());
  }
  const int bandCount = dataset->GetRasterCount();
  if (bandCount < 3) {
    return makeError("imagery '{}' has {} band(s); imagery needs red, green and blue", name,
                     bandCount);
  }
  for (int b = 1; b <= std::min(bandCount, 4); ++b) {
    if (dataset->GetRasterBand(b)->GetRasterDataType() != GDT_Byte) {
      return makeError("imagery '{}': band {} is not 8-bit", name, b);
    }
  }
  const int width = dataset->GetRasterXSize(), height = dataset->GetRasterYSize();
  if (width > options.maxSide || height > options.maxSide) {
    return makeError("imagery '{}' is {} x {} pixels; at most {} a side", name, width, height,
                     options.maxSide);
  }
  double gt[6] = {};
  if (dataset->GetGeoTransform(gt) != CE_None) {
    return makeError("imagery '{}' has no georeferencing (a GeoTIFF or a world file)", name);
  }
  if (Status northUp = checkNorthUpGeoTransform(std::to_array(gt)); !northUp) {
    return makeError("imagery '{}': {}", name, northUp.error().message);
  }
  std::string wkt;
  if (const OGRSpatialReference* srs = dataset->GetSpatialRef()) {
    char* text = nullptr;
    srs->exportToWkt(&text);
    wkt = text ? text : "";
    CPLFree(text);
    if (wkt.size() > kMaxWktBytes) {
      // Long WKT2 texts (ensembles): WKT1 is enough to rebuild the transformation.
      const char* wkt1[] = {"FORMAT=WKT1_GDAL", nullptr};
      text = nullptr;
      srs->exportToWkt(&text, wkt1);
      wkt = text ? text : "";
      CPLFree(text);
    }
    if (wkt.size() > kMaxWktBytes) return makeError("imagery '{}': its CRS description is too long", name);
    if (Result<std::unique_ptr<OGRCoordinateTransformation>> t = latLonTransformFrom(wkt, name); !t) {
      return t.error();
    }
  } else {
    const double slack = 1e-6 * 360.0;
    if (gt[0] < -180.0 - slack || gt[0] + width * gt[1] > 180.0 + slack ||
        gt[3] > 90.0 + slack || gt[3] + height * gt[5] < -90.0 - slack) {
      return makeError("imagery '{}' has no CRS and its grid is not within the globe's degrees",
                       name);
    }
  }

  // Level 0, premultiplied: colour times validity (a fourth band or the source's mask).
  std::vector<std::uint8_t> level(std::size_t(width) * height * 4);
  {
    Progress progress("read imagery", std::uint64_t(height));
    GDALRasterBand* validity = bandCount >= 4 &&
                                       dataset->GetRasterBand(4)->GetColorInterpretation() == GCI_AlphaBand
                                   ? dataset->GetRasterBand(4)
                                   : dataset->GetRasterBand(1)->GetMaskBand();
    constexpr int kRows = 256;
    for (int y = 0; y < height; y += kRows) {
      const int rows = std::min(kRows, height - y);
      std::uint8_t* at = &level[std::size_t(y) * width * 4];
      int bands[3] = {1, 2, 3};
      if (dataset->RasterIO(GF_Read, 0, y, width, rows, at, width, rows, GDT_Byte, 3, bands, 4,
                            std::int64_t(width) * 4, 1, nullptr) != CE_None ||
          validity->RasterIO(GF_Read, 0, y, width, rows, at + 3, width, rows, GDT_Byte, 4,
                             std::int64_t(width) * 4, nullptr) != CE_None) {
        return makeError("imagery '{}': reading rows {}..{}: {}", name, y, y + rows, gdal::lastError());
      }
      progress.advance(std::uint64_t(rows));
    }
  }
  for (std::size_t k = 0; k < level.size(); k += 4) {
    const unsigned a = level[k + 3] ? 255u : 0u;  // masks are 0 / 255; alpha bands thresholded
    level[k + 3] = std::uint8_t(a);
    if (a == 0) level[k] = level[k + 1] = level[k + 2] = 0;
  }

  const int levels = levelsFor(width, height, tileSize);
  std::vector<std::byte> header(kHeaderBytes);
  std::memcpy(header.data(), kMagic, sizeof(kMagic));
  put<std::uint32_t>(header, 8, kVersion);
  put<std::uint32_t>(header, 12, std::uint32_t(tileSize));
  put<std::uint32_t>(header, 16, std::uint32_t(width));
  put<std::uint32_t>(header, 20, std::uint32_t(height));
  put<std::uint32_t>(header, 24, std::uint32_t(levels));
  put<std::uint32_t>(header, 28, std::uint32_t(wkt.size()));
  std::error_code ec;
  put<std::uint64_t>(header, 32, std::uint64_t(std::filesystem::file_size(source, ec)));
  put<std::int64_t>(header, 40, modifiedNs(source));
  for (int k = 0; k < 6; ++k) put<double>(header, 48 + 8 * std::size_t(k), gt[k]);
  std::memcpy(header.data() + kWktOffset, wkt.data(), wkt.size());

  return writeFileAtomically(output, [&](const std::filesystem::path& temp) -> Status {
    std::FILE* file = std::fopen(temp.c_str(), "wb");
    if (!file) return makeError("cannot create '{}'", output.string());
    bool ok = std::fwrite(header.data(), 1, header.size(), file) == header.size();
    Progress progress("imagery pyramid", std::uint64_t(levels));
    int w = width, h = height;
    for (int m = 0; ok && m < levels; ++m) {
      if (m > 0) {
        level = halveLevel(level, w, h);
        w = halved(w, 1);
        h = halved(h, 1);
      }
      ok = writeLevelTiles(file, level, w, h, tileSize);
      progress.advance();
    }
    ok = ok && std::fflush(file) == 0 && fsync(fileno(file)) == 0;
    ok = (std::fclose(file) == 0) && ok;
    if (!ok) return makeError("writing '{}' failed (disk full?)", output.string());
    return {};
  });
}

int ImageryPyramid::levelWidth(int level) const { return halved(width_, level); }
int ImageryPyramid::levelHeight(int level) const { return halved(height_, level); }
int ImageryPyramid::tilesX(int level) const { return (levelWidth(level) + tileSize_ - 1) / tileSize_; }
int ImageryPyramid::tilesY(int level) const { return (levelHeight(level) + tileSize_ - 1) / tileSize_; }

std::span<const std::byte> ImageryPyramid::tile(int level, int x, int y) const {
  const std::size_t tileBytes = std::size_t(tileSize_) * tileSize_ * 4;
  std::size_t index = 0;
  for (int m = 0; m < level; ++m) index += std::size_t(tilesX(m)) * std::size_t(tilesY(m));
  index += std::size_t(y) * std::size_t(tilesX(level)) + std::size_t(x);
  return file_.bytes().subspan(kHeaderBytes + index * tileBytes, tileBytes);
}

Result<ImageryPyramid> ImageryPyramid::open(const std::filesystem::path& path) {
  Result<MappedFile> mapped = MappedFile::open(path);
  if (!mapped) return makeError("imagery pyramid: {}", mapped.error().message);
  const std::span<const std::byte> bytes = mapped->bytes();
  const std::string name = path.string();
  if (bytes.size() < kHeaderBytes || std::memcmp(bytes.data(), kMagic, sizeof(kMagic)) != 0) {
    return makeError("'{}' is not a Tellus imagery pyramid (.timagery)", name);
  }
  if (get<std::uint32_t>(bytes, 8) != kVersion) {
    return makeError("'{}': imagery pyramid version {} (this Tellus reads {})", name,
                     get<std::uint32_t>(bytes, 8), kVersion);
  }
  ImageryPyramid p;
  p.tileSize_ = int(get<std::uint32_t>(bytes, 12));
  p.width_ = int(get<std::uint32_t>(bytes, 16));
  p.height_ = int(get<std::uint32_t>(bytes, 20));
  p.levels_ = int(get<std::uint32_t>(bytes, 24));
  const std::uint32_t wktBytes = get<std::uint32_t>(bytes, 28);
  p.sourceBytes_ = get<std::uint64_t>(bytes, 32);
  p.sourceModifiedNs_ = get<std::int64_t>(bytes, 40);
  for (int k = 0; k < 6; ++k) p.geoTransform_[std::size_t(k)] = get<double>(bytes, 48 + 8 * std::size_t(k));
  if (p.tileSize_ < 16 || p.tileSize_ > 2048 || !std::has_single_bit(unsigned(p.tileSize_)) ||
      p.width_ < 1 || p.height_ < 1 || p.width_ > 1 << 20 || p.height_ > 1 << 20 ||
      p.levels_ != levelsFor(p.width_, p.height_, p.tileSize_) || wktBytes > kMaxWktBytes) {
    return makeError("'{}': corrupt imagery pyramid header", name);
  }
  std::size_t tiles = 0;
  for (int m = 0; m < p.levels_; ++m) tiles += std::size_t(p.tilesX(m)) * std::size_t(p.tilesY(m));
  const std::size_t expected = kHeaderBytes + tiles * std::size_t(p.tileSize_) * p.tileSize_ * 4;
  if (bytes.size() != expected) {
    return makeError("'{}' holds {} bytes, its header says {}: truncated or corrupt", name,
                     bytes.size(), expected);
  }
  const std::string wkt(reinterpret_cast<const char*>(bytes.data() + kWktOffset), wktBytes);
  gdal::ensureRegistered();
  Result<std::unique_ptr<OGRCoordinateTransformation>> t = latLonTransformFrom(wkt, name);
  if (!t) return t.error();
  p.transform_ = std::make_unique<Transform>();
  p.transform_->toLatLon = std::move(t.value());
  p.path_ = path;
  p.crsWkt_ = wkt;
  p.file_ = std::move(mapped.value());
  return p;
}

Result<ImageryPyramid::LatLon> ImageryPyramid::latLonAt(double x, double y) const {
  const auto& g = geoTransform_;
  double px = g[0] + x * g[1], py = g[3] + y * g[5];
  if (transform_ && transform_->toLatLon && !transform_->toLatLon->Transform(1, &px, &py)) {
    return makeError("imagery '{}': texel ({}, {}) has no latitude/longitude", path_.string(), x, y);
  }
  if (!std::isfinite(px) || !std::isfinite(py) || std::abs(py) > 90.0) {
    return makeError("imagery '{}': texel ({}, {}) lies beyond the globe", path_.string(), x, y);
  }
  return LatLon{py, px};
}

Result<ImageryPyramid> openCachedImageryPyramid(const std::filesystem::path& source,
                                                const std::filesystem::path& cacheFolder,
                                                const ImageryBuildOptions& options) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(source, ec)) {
    return makeError("imagery '{}' does not exist or is not a file", source.string());
  }
  std::string stem = source.stem().string();
  if (options.warp) {
    // The grid's own name: the same source draped on two stores is two pyramids.
    const ImageryWarpGrid& g = *options.warp;
    std::string key = fmt::format("{}|{}|{}|{:.17g},{:.17g},{:.17g},{:.17g},{:.17g},{:.17g}", g.crsWkt, g.width, g.height,
                                  g.geoTransform[0], g.geoTransform[1], g.geoTransform[2],
                                  g.geoTransform[3], g.geoTransform[4], g.geoTransform[5]);
    stem += fmt::format("-{:016x}", std::hash<std::string>{}(key));
  }
  const std::filesystem::path cached = cacheFolder / (stem + ".timagery");
  const std::uint64_t size = std::filesystem::file_size(source, ec);
  // Whether a pyramid on disk is the one asked for: built from this source as it is now, with
  // this tile size, on this grid (GDAL's warper derives the grid's geotransform from its extent
  // and size: equal to a millionth of a texel).
  const auto isTheOneAskedFor = [&](const ImageryPyramid& p) {
    const auto sameGeoTransform = [](const std::array<double, 6>& a, const std::array<double, 6>& b) {
      const double texel = std::max(std::abs(b[1]), std::abs(b[5]));
      for (int k = 0; k < 6; ++k) {
        if (std::abs(a[std::size_t(k)] - b[std::size_t(k)]) > 1e-6 * texel) return false;
      }
      return true;
    };
    const bool sameGrid = !options.warp || (p.width() == options.warp->width &&
                                            p.height() == options.warp->height &&
                                            sameGeoTransform(p.geoTransform(), options.warp->geoTransform));
    return p.sourceBytes() == size && sameGrid && p.sourceModifiedNs() == modifiedNs(source) &&
           p.tileSize() == options.tileSize;
  };
  if (std::filesystem::exists(cached, ec)) {
    Result<ImageryPyramid> existing = ImageryPyramid::open(cached);
    if (existing && isTheOneAskedFor(*existing)) return existing;
    spdlog::info("rebuilding '{}': {}", cached.string(),
                 existing ? "it was made from another version of the source, grid or tile size"
                          : existing.error().message);
  }
  std::filesystem::create_directories(cacheFolder, ec);
  if (ec) return makeError("cannot create '{}': {}", cacheFolder.string(), ec.message());
  spdlog::info("building the imagery pyramid of '{}' into '{}' (once)", source.string(),
               cached.string());
  if (Status built = buildImageryPyramid(source, cached, options); !built) return built.error();
  // The file is opened again by name: another process may have replaced it in between (with
  // the same source at another tile size, or the source changed again). What is opened is
  // checked as a cached one is, never taken on trust.
  Result<ImageryPyramid> built = ImageryPyramid::open(cached);
  if (built && !isTheOneAskedFor(*built)) {
    return makeError("imagery cache '{}' was replaced by another process while it was built; "
                     "run again", cached.string());
  }
  return built;
}

}  // namespace tellus
