#pragma once
// Small helpers shared by the GDAL-facing files of tellus_dem (private to this library).
#include <memory>
#include <string>

#include <gdal_priv.h>

namespace tellus::gdal {

// Registers GDAL's drivers once and routes GDAL's own messages to the debug log
// (callers report failures with lastError()). Thread-safe.
void ensureRegistered();

// GDAL's last error message on this thread, or "unknown GDAL error".
std::string lastError();
// The same, empty when GDAL gave none.
std::string lastErrorMessage();

struct DatasetCloser {
  void operator()(GDALDataset* dataset) const { GDALClose(GDALDataset::ToHandle(dataset)); }
};
using DatasetPtr = std::unique_ptr<GDALDataset, DatasetCloser>;

}  // namespace tellus::gdal
