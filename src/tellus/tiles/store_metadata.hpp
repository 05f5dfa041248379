#pragma once
// What a tile store says about itself: pyramid geometry, codec, vertical quantum, ground
// spacing, georeferencing and how it was built. Stored as JSON inside the store file.
#include <string>
#include <vector>

#include "tellus/core/result.hpp"
#include "tellus/dem/height_grid.hpp"
#include "tellus/tiles/pyramid_layout.hpp"

namespace tellus {

// Metres per stored integer step a store may have: from a micrometre (heights up to about
// 2 km still fit 32 bits) to 100 m (coarser than any DEM's precision).
inline constexpr double kMinQuantumM = 1e-6;
inline constexpr double kMaxQuantumM = 100.0;

struct StoreMetadata {
  PyramidLayout layout;
  std::string codec;      // codec name (tile_codec.hpp)
  double quantumM = 1.0;  // metres per integer sample step; height = sample * quantumM
  // Guaranteed bound on |stored height - input height| for every level-0 sample, metres:
  // 0 when the codec is lossless and the input heights are multiples of the quantum.
  double maxErrorM = 0.0;
  std::uint32_t maxErrorSteps = 0;  // the codec's own bound, in quanta
  // True when the codec bounds nothing (fractal without residual): maxErrorM is then the
  // largest error the build measured, not a guarantee.
  bool maxErrorMeasured = false;
  int zstdLevel = 0;
  double spacingXM = 1.0;  // level-0 ground spacing, metres (level L: times 2^L)
  double spacingYM = 1.0;
  GeoReference georef;      // of the level-0 grid
  float minHeightM = 0.0f;  // over all level-0 data
  float maxHeightM = 0.0f;
  std::size_t filledVoidCount = 0;
  std::vector<std::string> sources;  // input files as given
  std::string producer;              // "tellus 0.1.0"
};

std::string metadataToJson(const StoreMetadata& metadata);
// Parses and validates every field's meaning (ranges, integral counts, min <= max, levels that
// match the pyramid, a geotransform with area); errors say which field is wrong. The CRS WKT is
// parsed by `tellus verify` (GDAL's checkGeoReference), not here: this library is GDAL-free.
Result<StoreMetadata> metadataFromJson(std::string_view json);

}  // namespace tellus
