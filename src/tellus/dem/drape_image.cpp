#include "tellus/dem/drape_image.hpp"

#include "tellus/dem/lat_lon_raster.hpp"

namespace tellus {

Result<DrapeImage> loadDrapeImage(const std::filesystem::path& path, int maxSide) {
  LatLonRasterBounds bounds;
  Result<std::vector<std::uint8_t>> pixels = readLatLonRaster(
      path, "drape",
      "a georeferenced RGB image: red, green and blue (a GeoTIFF, or a JPEG or PNG with a world file)",
      3, maxSide, bounds);
  if (!pixels) return pixels.error();
  DrapeImage drape;
  drape.westDeg = bounds.westDeg;
  drape.eastDeg = bounds.eastDeg;
  drape.northDeg = bounds.northDeg;
  drape.southDeg = bounds.southDeg;
  drape.image = RgbImage(bounds.width, bounds.height);
  drape.image.pixels = std::move(pixels.value());
  return drape;
}

}  // namespace tellus
