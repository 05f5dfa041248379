#include "tellus/dem/gdal_support.hpp"

#include "tellus/core/input_file.hpp"
#include "tellus/dem/raster_diagnosis.hpp"

#include <mutex>

#include <cpl_error.h>
#include <ogr_spatialref.h>
#include <fmt/format.h>
#include <spdlog/spdlog.h>

namespace tellus::gdal {
namespace {

void CPL_STDCALL logGdalMessage(CPLErr level, CPLErrorNum number, const char* message) {
  spdlog::debug("GDAL ({}, {}): {}", int(level), number, message);
}

}  // namespace

void ensureRegistered() {
  static std::once_flag once;
  std::call_once(once, [] {
    GDALAllRegister();
    CPLSetErrorHandler(logGdalMessage);
  });
}

const std::string& wgs84Wkt() {
  static const std::string wkt = [] {
    OGRSpatialReference srs;
    srs.SetWellKnownGeogCS("WGS84");
    char* text = nullptr;
    srs.exportToWkt(&text);
    std::string s = text ? text : "";
    CPLFree(text);
    return s;
  }();
  return wkt;
}

std::string lastErrorMessage() {
  const char* message = CPLGetLastErrorMsg();
  return message ? std::string(message) : std::string();
}

std::string lastError() {
  const std::string message = lastErrorMessage();
  return message.empty() ? std::string("GDAL gave no reason (the file may be truncated or corrupt)")
                         : message;
}

Result<DatasetPtr> openRasterFile(const std::filesystem::path& path, std::string_view role,
                                  const std::string& expected) {
  ensureRegistered();
  if (Status regular = checkRegularInput(path); !regular) {
    return makeError("{}: {}", role, regular.error().message);
  }
  CPLErrorReset();
  DatasetPtr dataset(GDALDataset::Open(path.c_str(), GDAL_OF_RASTER | GDAL_OF_READONLY));
  if (!dataset) {
    return makeError("{} '{}': cannot read it as a raster: {}", role, path.string(),
                     explainUnreadableRaster(path, lastErrorMessage(), expected));
  }
  return dataset;
}

}  // namespace tellus::gdal
