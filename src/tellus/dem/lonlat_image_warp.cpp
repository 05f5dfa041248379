#include "tellus/dem/lonlat_image_warp.hpp"

#include <gdal_utils.h>
#include <ogr_spatialref.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "tellus/dem/gdal_support.hpp"

namespace tellus {

namespace {

struct WarpOptionsDeleter {
  void operator()(GDALWarpAppOptions* o) const { GDALWarpAppOptionsFree(o); }
};
struct TranslateOptionsDeleter {
  void operator()(GDALTranslateOptions* o) const { GDALTranslateOptionsFree(o); }
};

// The source's CRS as gdalwarp's -s_srs wants it: its own, or WGS 84 for a grid without one
// that lies within the globe's degrees. Empty with `error` set when neither holds.
std::string sourceCrs(GDALDataset& dataset, const std::string& name, std::string& error) {
  if (dataset.GetSpatialRef()) return {};  // gdalwarp reads it
  double gt[6] = {};
  if (dataset.GetGeoTransform(gt) != CE_None) {
    error = "'" + name + "' has no georeferencing: a texture must say where it lies (a GeoTIFF, or a "
            "JPEG or PNG with a world file)";
    return {};
  }
  const double east = gt[0] + dataset.GetRasterXSize() * gt[1];
  const double south = gt[3] + dataset.GetRasterYSize() * gt[5];
  if (gt[0] >= -180.5 && east <= 180.5 && south >= -90.5 && gt[3] <= 90.5 && gt[1] > 0.0 && gt[5] < 0.0) {
    return "EPSG:4326";
  }
  error = "'" + name + "' has no coordinate system and its grid is not in degrees (give it one with "
          "gdal_edit.py -a_srs)";
  return {};
}

}  // namespace

Result<LonLatImage> warpImageToLonLat(const std::filesystem::path& source, const LonLatImageRequest& request) {
  gdal::ensureRegistered();
  const std::string name = source.string();
  if (request.width < 1 || request.height < 1 || request.width > 16384 || request.height > 16384 ||
      !(request.eastDeg > request.westDeg) || !(request.northDeg > request.southDeg) ||
      request.westDeg < -180.0 || request.eastDeg > 180.0 || request.southDeg < -90.0 || request.northDeg > 90.0) {
    return makeError("texture of {} x {} pixels over {}..{} E, {}..{} N: out of range", request.width,
                     request.height, request.westDeg, request.eastDeg, request.southDeg, request.northDeg);
  }
  Result<gdal::DatasetPtr> opened = gdal::openRasterFile(
      source, "texture", "a georeferenced RGB image (a GeoTIFF, or a JPEG or PNG with a world file)");
  if (!opened) return opened.error();
  GDALDataset& dataset = *opened.value();
  if (dataset.GetRasterCount() < 3) {
    return makeError("'{}' has {} band(s): a texture needs red, green and blue", name, dataset.GetRasterCount());
  }
  for (int band = 1; band <= 3; ++band) {
    if (dataset.GetRasterBand(band)->GetRasterDataType() != GDT_Byte) {
      return makeError("'{}': band {} is not 8-bit; a texture is an 8-bit RGB image", name, band);
    }
  }
  std::string crsError;
  const std::string crs = sourceCrs(dataset, name, crsError);
  if (!crsError.empty()) return makeError("{}", crsError);

  // Red, green, blue and the source's coverage (its mask or alpha, and what lies outside it)
  // as a fourth band.
  GDALDriver* mem = GetGDALDriverManager()->GetDriverByName("MEM");
  gdal::DatasetPtr target(mem->Create("", request.width, request.height, 4, GDT_Byte, nullptr));
  if (!target) return makeError("cannot create a texture of {} x {}: {}", request.width, request.height, gdal::lastError());
  const double gt[6] = {request.westDeg, (request.eastDeg - request.westDeg) / request.width, 0.0,
                        request.northDeg, 0.0, -(request.northDeg - request.southDeg) / request.height};
  target->SetGeoTransform(const_cast<double*>(gt));
  OGRSpatialReference wgs84;
  wgs84.importFromEPSG(4326);
  wgs84.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
  target->SetSpatialRef(&wgs84);
  target->GetRasterBand(4)->SetColorInterpretation(GCI_AlphaBand);
  // Bands 1..3 alone (a fourth, an alpha or anything else, is left out), with the source's
  // mask, as a virtual dataset: GDAL 3.6's warper has no -srcband.
  const char* translateArgv[] = {"-of", "VRT", "-b", "1", "-b", "2", "-b", "3", "-q", nullptr};
  std::unique_ptr<GDALTranslateOptions, TranslateOptionsDeleter> translateOptions(
      GDALTranslateOptionsNew(const_cast<char**>(translateArgv), nullptr));
  int translateError = 0;
  gdal::DatasetPtr rgb(GDALDataset::FromHandle(
      GDALTranslate("", GDALDataset::ToHandle(&dataset), translateOptions.get(), &translateError)));
  if (!rgb) return makeError("'{}': GDAL could not read its red, green and blue bands: {}", name, gdal::lastError());
  std::vector<const char*> argv = {"-r", "bilinear", "-dstalpha", "-q"};
  if (!crs.empty()) {
    argv.push_back("-s_srs");
    argv.push_back(crs.c_str());
  }
  argv.push_back(nullptr);
  std::unique_ptr<GDALWarpAppOptions, WarpOptionsDeleter> options(
      GDALWarpAppOptionsNew(const_cast<char**>(argv.data()), nullptr));
  if (!options) return makeError("'{}': GDAL refused the warp options: {}", name, gdal::lastError());
  GDALDatasetH sourceHandle = GDALDataset::ToHandle(rgb.get());
  int usageError = 0;
  CPLErrorReset();
  if (!GDALWarp(nullptr, GDALDataset::ToHandle(target.get()), 1, &sourceHandle, options.get(), &usageError)) {
    return makeError("'{}': GDAL could not warp it to latitude/longitude: {}", name, gdal::lastError());
  }
  const std::size_t pixels = std::size_t(request.width) * std::size_t(request.height);
  std::vector<std::uint8_t> rgba(4 * pixels);
  if (target->RasterIO(GF_Read, 0, 0, request.width, request.height, rgba.data(), request.width, request.height,
                       GDT_Byte, 4, nullptr, 4, 4 * request.width, 1, nullptr) != CE_None) {
    return makeError("cannot read the warped texture: {}", gdal::lastError());
  }
  LonLatImage out;
  out.image = RgbImage(request.width, request.height);
  std::size_t covered = 0;
  for (std::size_t k = 0; k < pixels; ++k) {
    const int alpha = rgba[4 * k + 3];
    if (alpha > 0) ++covered;
    for (std::size_t c = 0; c < 3; ++c) {
      out.image.pixels[3 * k + c] =
          std::uint8_t((rgba[4 * k + c] * alpha + request.fill[c] * (255 - alpha) + 127) / 255);
    }
  }
  out.coveredFraction = double(covered) / double(pixels);
  if (covered == 0) {
    return makeError("'{}' covers none of {:.4f}..{:.4f} E, {:.4f}..{:.4f} N: nothing to drape there", name,
                     request.westDeg, request.eastDeg, request.southDeg, request.northDeg);
  }
  return out;
}

}  // namespace tellus
