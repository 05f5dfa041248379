#pragma once
// Small helpers shared by the GDAL-facing files of tellus_dem (private to this library).
#include <filesystem>
#include <memory>
#include <string_view>
#include <string>

#include <gdal_priv.h>

#include "tellus/core/result.hpp"

namespace tellus::gdal {

// Registers GDAL's drivers once and routes GDAL's own messages to the debug log
// (callers report failures with lastError()). Thread-safe.
void ensureRegistered();

// GDAL's last error message on this thread, or, when GDAL gave none, a sentence saying so
// ("GDAL gave no reason: the file may be truncated or corrupt").
std::string lastError();
// The same, empty when GDAL gave none.
std::string lastErrorMessage();

// WGS 84 latitude/longitude (EPSG:4326) as WKT, made once. Thread-safe.
const std::string& wgs84Wkt();

struct DatasetCloser {
  void operator()(GDALDataset* dataset) const { GDALClose(GDALDataset::ToHandle(dataset)); }
};
using DatasetPtr = std::unique_ptr<GDALDataset, DatasetCloser>;

// Opens `path` read-only as a raster: a FIFO or device is refused before anything opens it
// (never a hang), and a file GDAL cannot read gets an explanation (raster_diagnosis.hpp):
// "<role> 'PATH': cannot read it as a raster: it is not in a raster format GDAL recognises
// (1234 bytes starting with 23 21 ...); expected <expected>". Paths under /vsi are GDAL's own.
Result<DatasetPtr> openRasterFile(const std::filesystem::path& path, std::string_view role,
                                  const std::string& expected);

}  // namespace tellus::gdal
