#include "tellus/dem/decoded_heights_copy.hpp"

#include <cpl_string.h>
#include <gdal_priv.h>

#include <algorithm>
#include <limits>
#include <vector>

#include "tellus/core/progress.hpp"
#include "tellus/dem/dem_source.hpp"
#include "tellus/dem/gdal_support.hpp"

namespace tellus {
namespace fs = std::filesystem;

namespace {

constexpr int kRowsPerRead = 256;

Status copyRows(DemSource& source, GDALDataset& copy) {
  const DemSourceInfo& info = source.info();
  std::vector<float> rows;
  Progress progress("decode", std::uint64_t(info.height));
  for (int row = 0; row < info.height; row += kRowsPerRead) {
    const int count = std::min(kRowsPerRead, info.height - row);
    rows.resize(std::size_t(info.width) * std::size_t(count));
    if (Status s = source.readRows(row, count, rows); !s) return s;
    if (copy.GetRasterBand(1)->RasterIO(GF_Write, 0, row, info.width, count, rows.data(),
                                        info.width, count, GDT_Float32, 0, 0) != CE_None) {
      return makeError("cannot write the decoded copy of '{}': {}", info.name, gdal::lastError());
    }
    progress.set(std::uint64_t(row + count));
  }
  return {};
}

}  // namespace

Status writeDecodedHeightsCopy(const fs::path& input, HeightEncoding encoding,
                               const fs::path& output) {
  DemLoadOptions load;
  load.encoding = encoding;
  Result<std::unique_ptr<DemSource>> opened = DemSource::open({input}, load);
  if (!opened) return opened.error();
  DemSource& source = *opened.value();
  const DemSourceInfo& info = source.info();
  GDALDriver* gtiff = GetGDALDriverManager()->GetDriverByName("GTiff");
  CPLStringList options;
  options.SetNameValue("TILED", "YES");
  options.SetNameValue("BIGTIFF", "IF_SAFER");
  gdal::DatasetPtr copy(
      gtiff->Create(output.c_str(), info.width, info.height, 1, GDT_Float32, options.List()));
  if (!copy) {
    return makeError("cannot create the decoded copy of '{}': {}", info.name, gdal::lastError());
  }
  if (info.georef.hasGeoTransform) {
    std::array<double, 6> gt = info.georef.geoTransform;
    copy->SetGeoTransform(gt.data());
  }
  if (!info.georef.crsWkt.empty()) copy->SetProjection(info.georef.crsWkt.c_str());
  copy->GetRasterBand(1)->SetNoDataValue(std::numeric_limits<double>::quiet_NaN());
  Status copied = copyRows(source, *copy);
  CPLErrorReset();
  copy.reset();  // flushes and closes
  if (copied && CPLGetLastErrorType() >= CE_Failure) {
    copied = makeError("cannot write the decoded copy of '{}': {}", info.name, gdal::lastError());
  }
  if (!copied) {
    std::error_code ec;
    fs::remove(output, ec);
  }
  return copied;
}

}  // namespace tellus
