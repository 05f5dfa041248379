#pragma once
// What a global store (global_store.hpp) says about itself, stored as JSON inside the .tstore
// container ("format": "tellus-global-store"), GDAL-free.
#include <cstdint>
#include <string>
#include <vector>

#include "tellus/core/result.hpp"
#include "tellus/tiles/global_tiling.hpp"

namespace tellus {

// One input of the store: where it lies and down to which depth it feeds tiles.
struct GlobalStoreSource {
  std::string path;        // as given to the build
  GeoBounds bounds;        // the area its samples span, degrees
  double spacingDeg = 0.0;  // its sample spacing, degrees
  int depth = 0;           // tiles exist down to this depth where it lies (its native depth)
};

// The widest edge blending band a build accepts, metres (a continent's width).
inline constexpr double kMaxEdgeBlendM = 1'000'000.0;

struct GlobalStoreMetadata {
  int tileCells = 256;  // cells per tile side; a tile holds (tileCells + 1)^2 samples
  int deepestDepth = 0;
  std::string codec;
  double quantumM = 0.01;  // metres per stored integer step
  double maxErrorM = 0.0;  // the codec's bound on |stored - warped height| (+ rounding)
  std::uint32_t maxErrorSteps = 0;
  int zstdLevel = 0;
  float minHeightM = 0.0f;  // over every stored sample
  float maxHeightM = 0.0f;
  float northPoleM = 0.0f;  // every sample on a pole has this height
  float southPoleM = 0.0f;
  // Samples that no source covered: stored at 0 m (mean sea level).
  std::uint64_t uncoveredSamples = 0;
  // A source's samples of exactly 0 m (SRTM's sea) yielded to a later source's sea floor
  // (LatLonWarper::open's zeroYieldsToSeaFloor). Absent in older stores: false.
  bool zeroYieldsToSeaFloor = false;
  // Metres over which each source that does not cover the globe faded into the coarser ones
  // inside its edges (GlobalBuildOptions::edgeBlendM). Absent in older stores: 0.
  double edgeBlendM = 0.0;
  std::vector<std::uint64_t> tilesPerDepth;  // [depth]
  std::vector<GlobalStoreSource> sources;    // finest first: the order of precedence
  std::string producer;
  // Older stores recorded their build time; it is no longer written (a store's bytes depend on
  // its inputs only). 0 when absent.
  double buildSeconds = 0.0;
};

std::string globalMetadataToJson(const GlobalStoreMetadata& metadata);
// Parses and checks every field's meaning; errors say which field is wrong.
Result<GlobalStoreMetadata> globalMetadataFromJson(std::string_view json);

}  // namespace tellus
