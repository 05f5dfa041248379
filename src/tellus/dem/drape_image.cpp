#include "tellus/dem/drape_image.hpp"

#include <spdlog/spdlog.h>

#include "tellus/core/geotransform_check.hpp"
#include "tellus/dem/gdal_support.hpp"

namespace tellus {

Result<DrapeImage> loadDrapeImage(const std::filesystem::path& path, int maxSide) {
  gdal::ensureRegistered();
  const std::string name = path.string();
  Result<gdal::DatasetPtr> opened = gdal::openRasterFile(
      path, "drape", "a georeferenced RGB image (a GeoTIFF, or a JPEG or PNG with a world file)");
  if (!opened) return opened.error();
  gdal::DatasetPtr dataset = std::move(opened.value());
  if (dataset->GetRasterCount() < 3) {
    return makeError("drape '{}' has {} band(s); a colour drape needs red, green and blue", name,
                     dataset->GetRasterCount());
  }
  for (int b = 1; b <= 3; ++b) {
    if (dataset->GetRasterBand(b)->GetRasterDataType() != GDT_Byte) {
      return makeError("drape '{}': band {} is not 8-bit", name, b);
    }
  }
  const int width = dataset->GetRasterXSize(), height = dataset->GetRasterYSize();
  if (width > maxSide || height > maxSide) {
    return makeError("drape '{}' is {} x {} pixels; at most {} a side fit a texture", name, width,
                     height, maxSide);
  }
  double gt[6] = {};
  if (dataset->GetGeoTransform(gt) != CE_None) {
    return makeError("drape '{}' has no georeferencing (a world file such as .jgw, or a GeoTIFF)",
                     name);
  }
  if (Status northUp = checkNorthUpGeoTransform(std::to_array(gt)); !northUp) {
    return makeError("drape '{}': {}", name, northUp.error().message);
  }
  DrapeImage drape;
  drape.westDeg = gt[0];
  drape.northDeg = gt[3];
  drape.eastDeg = gt[0] + width * gt[1];
  drape.southDeg = gt[3] + height * gt[5];
  const OGRSpatialReference* srs = dataset->GetSpatialRef();
  if (srs && !srs->IsGeographic()) {
    return makeError("drape '{}' is in a projected CRS; drapes are latitude/longitude grids "
                     "(gdalwarp -t_srs EPSG:4326 turns it into one)",
                     name);
  }
  const double slack = 1e-6 * 360.0;
  if (drape.westDeg < -180.0 - slack || drape.eastDeg > 180.0 + slack ||
      drape.southDeg < -90.0 - slack || drape.northDeg > 90.0 + slack) {
    return makeError("drape '{}' spans {}..{} E, {}..{} N: beyond the globe", name, drape.westDeg,
                     drape.eastDeg, drape.southDeg, drape.northDeg);
  }
  if (!srs) spdlog::debug("drape '{}' has no CRS: taken as WGS 84 latitude/longitude", name);
  drape.image = RgbImage(width, height);
  int bands[3] = {1, 2, 3};
  if (dataset->RasterIO(GF_Read, 0, 0, width, height, drape.image.pixels.data(), width, height,
                        GDT_Byte, 3, bands, 3, std::int64_t(width) * 3, 1, nullptr) != CE_None) {
    return makeError("drape '{}': {}", name, gdal::lastError());
  }
  return drape;
}

}  // namespace tellus
