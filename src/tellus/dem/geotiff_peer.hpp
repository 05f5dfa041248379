#pragma once
// GDAL's own tiled GeoTIFF compression as a yardstick for Tellus' tile codecs (tellus bench
// codecs): writes a grid with one creation-option set, reads it back, and times both.
#include <filesystem>
#include <string>
#include <vector>

#include "tellus/core/result.hpp"
#include "tellus/dem/height_grid.hpp"

namespace tellus {

struct GeoTiffPeer {
  std::string name;                  // "gdal-zstd-pred2"
  std::vector<std::string> options;  // GTiff creation options, "KEY=VALUE"
};

struct GeoTiffPeerResult {
  std::uint64_t bytes = 0;     // file size
  double encodeSeconds = 0.0;  // median over repeats, one thread
  double decodeSeconds = 0.0;
  std::vector<float> decoded;  // heights read back, metres
};

// `integerSamples`: the heights are whole metres; write Int16 (when they fit), as SRTM is stored,
// instead of Float32.
Result<GeoTiffPeerResult> measureGeoTiffPeer(const HeightGrid& grid, bool integerSamples,
                                             const GeoTiffPeer& peer,
                                             const std::filesystem::path& scratchFolder,
                                             int repeats);

}  // namespace tellus
