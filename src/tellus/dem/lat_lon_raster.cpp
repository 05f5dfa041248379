#include "tellus/dem/lat_lon_raster.hpp"

#include <spdlog/spdlog.h>

#include "tellus/core/geotransform_check.hpp"
#include "tellus/dem/gdal_support.hpp"

namespace tellus {

Result<std::vector<std::uint8_t>> readLatLonRaster(const std::filesystem::path& path,
                                                   const std::string& role,
                                                   const std::string& expected, int bands,
                                                   int maxSide, LatLonRasterBounds& bounds) {
  gdal::ensureRegistered();
  const std::string name = path.string();
  Result<gdal::DatasetPtr> opened = gdal::openRasterFile(path, role, expected);
  if (!opened) return opened.error();
  gdal::DatasetPtr dataset = std::move(opened.value());
  if (dataset->GetRasterCount() < bands) {
    return makeError("{} '{}' has {} band(s); it needs {} ({})", role, name,
                     dataset->GetRasterCount(), bands, expected);
  }
  for (int b = 1; b <= bands; ++b) {
    if (dataset->GetRasterBand(b)->GetRasterDataType() != GDT_Byte) {
      return makeError("{} '{}': band {} is not 8-bit", role, name, b);
    }
  }
  const int width = dataset->GetRasterXSize(), height = dataset->GetRasterYSize();
  if (width > maxSide || height > maxSide) {
    return makeError("{} '{}' is {} x {} pixels; at most {} a side", role, name, width, height,
                     maxSide);
  }
  double gt[6] = {};
  if (dataset->GetGeoTransform(gt) != CE_None) {
    return makeError("{} '{}' has no georeferencing (a world file such as .jgw, or a GeoTIFF)",
                     role, name);
  }
  if (Status northUp = checkNorthUpGeoTransform(std::to_array(gt)); !northUp) {
    return makeError("{} '{}': {}", role, name, northUp.error().message);
  }
  bounds.bandCount = dataset->GetRasterCount();
  bounds.width = width;
  bounds.height = height;
  bounds.westDeg = gt[0];
  bounds.northDeg = gt[3];
  bounds.eastDeg = gt[0] + width * gt[1];
  bounds.southDeg = gt[3] + height * gt[5];
  const OGRSpatialReference* srs = dataset->GetSpatialRef();
  if (srs && !srs->IsGeographic()) {
    return makeError("{} '{}' is in a projected CRS; it must be a latitude/longitude grid "
                     "(gdalwarp -t_srs EPSG:4326 turns it into one)",
                     role, name);
  }
  const double slack = 1e-6 * 360.0;
  if (bounds.westDeg < -180.0 - slack || bounds.eastDeg > 180.0 + slack ||
      bounds.southDeg < -90.0 - slack || bounds.northDeg > 90.0 + slack) {
    return makeError("{} '{}' spans {}..{} E, {}..{} N: beyond the globe", role, name,
                     bounds.westDeg, bounds.eastDeg, bounds.southDeg, bounds.northDeg);
  }
  if (!srs) spdlog::debug("{} '{}' has no CRS: taken as WGS 84 latitude/longitude", role, name);
  std::vector<std::uint8_t> pixels(std::size_t(width) * std::size_t(height) * std::size_t(bands));
  std::vector<int> bandList(static_cast<std::size_t>(bands));
  for (int b = 0; b < bands; ++b) bandList[std::size_t(b)] = b + 1;
  if (dataset->RasterIO(GF_Read, 0, 0, width, height, pixels.data(), width, height, GDT_Byte,
                        bands, bandList.data(), bands, std::int64_t(width) * bands, 1,
                        nullptr) != CE_None) {
    return makeError("{} '{}': {}", role, name, gdal::lastError());
  }
  return pixels;
}

}  // namespace tellus
