#include "tellus/dem/geotiff_peer.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>

#include <cpl_conv.h>

#include "tellus/core/stopwatch.hpp"
#include "tellus/dem/gdal_support.hpp"

namespace tellus {
namespace fs = std::filesystem;

namespace {
double median(std::vector<double> values) {
  std::sort(values.begin(), values.end());
  return values[values.size() / 2];
}
}  // namespace

Result<GeoTiffPeerResult> measureGeoTiffPeer(const HeightGrid& grid, bool integerSamples,
                                             const GeoTiffPeer& peer, const fs::path& scratchFolder,
                                             int repeats) {
  gdal::ensureRegistered();
  CPLSetConfigOption("GDAL_NUM_THREADS", "1");
  const HeightRange range = grid.heightRange();
  const bool asInt16 = integerSamples && range.minM >= -32768.0f && range.maxM <= 32767.0f;
  const GDALDataType type = asInt16 ? GDT_Int16 : GDT_Float32;
  GDALDriver* mem = GetGDALDriverManager()->GetDriverByName("MEM");
  GDALDriver* gtiff = GetGDALDriverManager()->GetDriverByName("GTiff");
  gdal::DatasetPtr source(mem->Create("", grid.width, grid.height, 1, type, nullptr));
  if (!source) return makeError("cannot create an in-memory raster: {}", gdal::lastError());
  if (source->GetRasterBand(1)->RasterIO(GF_Write, 0, 0, grid.width, grid.height,
                                         const_cast<float*>(grid.heights.data()), grid.width,
                                         grid.height, GDT_Float32, 0, 0) != CE_None) {
    return makeError("cannot fill the in-memory raster: {}", gdal::lastError());
  }
  char** options = nullptr;
  options = CSLSetNameValue(options, "TILED", "YES");
  options = CSLSetNameValue(options, "BLOCKXSIZE", "256");
  options = CSLSetNameValue(options, "BLOCKYSIZE", "256");
  for (const std::string& option : peer.options) options = CSLAddString(options, option.c_str());
  const fs::path file = scratchFolder / (peer.name + ".tif");

  GeoTiffPeerResult result;
  std::vector<double> encodeTimes, decodeTimes;
  result.decoded.resize(grid.heights.size());
  for (int r = 0; r < repeats; ++r) {
    Stopwatch start;
    gdal::DatasetPtr written(
        gtiff->CreateCopy(file.c_str(), source.get(), FALSE, options, nullptr, nullptr));
    written.reset();  // flush and close inside the timing
    encodeTimes.push_back(
        start.elapsedS());
    if (!fs::exists(file)) {
      CSLDestroy(options);
      return makeError("GDAL could not write {}: {}", peer.name, gdal::lastError());
    }
    start.restart();
    gdal::DatasetPtr read(GDALDataset::FromHandle(GDALOpen(file.c_str(), GA_ReadOnly)));
    const bool ok = read && read->GetRasterBand(1)->RasterIO(
                                GF_Read, 0, 0, grid.width, grid.height, result.decoded.data(),
                                grid.width, grid.height, GDT_Float32, 0, 0) == CE_None;
    read.reset();
    decodeTimes.push_back(
        start.elapsedS());
    if (!ok) {
      CSLDestroy(options);
      return makeError("GDAL could not read back {}: {}", peer.name, gdal::lastError());
    }
  }
  CSLDestroy(options);
  result.bytes = fs::file_size(file);
  fs::remove(file);
  result.encodeSeconds = median(encodeTimes);
  result.decodeSeconds = median(decodeTimes);
  return result;
}

}  // namespace tellus
