// libFuzzer target: DEM loading (GDAL, then Tellus' void handling, encodings, georeferencing
// checks and statistics) on small in-memory rasters. Input: [name u8][encoding u8][file bytes].
// The first byte names the file in GDAL's /vsimem/ (a GeoTIFF, an SRTM tile, a PNG, an ASCII
// grid...), the second picks the height encoding. Loading must fail with a message or give a
// grid; rasters of more than 2^16 samples are only opened and scanned in a sample of rows, as
// `tellus info` does. Tellus' memory budget is 512 MiB here (TELLUS_MEMORY_LIMIT_MB) and GDAL's
// block cache 64 MiB, within libFuzzer's 2 GiB limit: a file whose blocks or grid would not fit
// must be refused by Tellus, not allocated.
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <string>

#include <cpl_vsi.h>

#include "fuzz_input.hpp"
#include "tellus/dem/dem_loader.hpp"
#include "tellus/dem/dem_source.hpp"

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  ::setenv("TELLUS_MEMORY_LIMIT_MB", "512", 1);
  tellus::DemSource::setReadCacheLimit(std::size_t(64) << 20);
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const std::array<const char*, 6> kNames = {"/vsimem/fuzz.tif", "/vsimem/N37E127.hgt",
                                                    "/vsimem/fuzz.png", "/vsimem/fuzz.asc",
                                                    "/vsimem/fuzz.bt",  "/vsimem/fuzz.dem"};
  tellus::fuzz::FuzzInput input(data, size);
  const std::string name = kNames[input.take<std::uint8_t>() % kNames.size()];
  const auto encoding = tellus::HeightEncoding(input.take<std::uint8_t>() % 3);
  const std::span<const std::byte> bytes = input.rest();
  VSILFILE* file = VSIFileFromMemBuffer(name.c_str(), reinterpret_cast<GByte*>(const_cast<std::byte*>(bytes.data())),
                                        vsi_l_offset(bytes.size()), FALSE);
  if (!file) return 0;
  VSIFCloseL(file);
  tellus::DemLoadOptions options;
  options.encoding = encoding;
  auto source = tellus::DemSource::open({name}, options);
  if (source) {
    const tellus::DemSourceInfo& info = source.value()->info();
    if (!(info.spacingXM > 0.0 && std::isfinite(info.spacingXM))) std::abort();
    const double samples = double(info.width) * double(info.height);
    (void)source.value()->scanStatistics(std::uint64_t(1) << 16);
    source.value().reset();
    if (samples <= double(1 << 16)) {
      auto grid = tellus::loadDem({name}, options);
      if (grid) {
        for (float h : grid->heights) {
          if (!std::isfinite(h)) std::abort();  // voids are filled, nothing else is NaN
        }
      }
    }
  }
  VSIUnlink(name.c_str());
  return 0;
}
