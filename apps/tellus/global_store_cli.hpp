#pragma once
// The CLI's side of global stores (tiles/global_store.hpp): what info, verify, export and the
// globe renderers do with one.
#include <optional>
#include <string>

#include "tellus/core/geo_camera.hpp"
#include "tellus/core/result.hpp"
#include "cli_support.hpp"
#include "tellus/dem/height_grid.hpp"
#include "tellus/eval/path_benchmark.hpp"
#include "tellus/tiles/global_store.hpp"

namespace tellus::cli {

int printGlobalStoreInfo(const DemInputOptions& input);
// Checks every tile (checksum, decoding, index statistics) and the store's promises: edges
// shared bit for bit with stored neighbours (across the antimeridian too), samples equal to
// the parent's where they coincide, pole rows at the pole height, and each parent's error at
// least its stored children's deviation from its surface. Prints problems; 0 when all good.
int verifyGlobalStore(const DemInputOptions& input);

// "WEST,SOUTH,EAST,NORTH" in degrees.
Result<GeoBounds> parseGeoBounds(const std::string& text);

// Which part of a global store to turn into a grid: an explicit depth and/or region, else what
// a camera's view can show (geoViewFootprint) at the deepest depth that fits `maxSamples`.
struct GlobalRegionRequest {
  std::optional<int> depth;
  std::optional<GeoBounds> region;
  std::optional<GeoCamera> camera;
  double aspect = 16.0 / 9.0;  // the view's width / height
  std::uint64_t maxSamples = std::uint64_t(32) << 20;
};
// A request from the command line's --store-depth (negative: none) and --region (empty: none).
Result<GlobalRegionRequest> regionRequest(int storeDepth, const std::string& region,
                                          const std::optional<GeoCamera>& camera, double aspect,
                                          std::uint64_t maxSamples);

struct GlobalRegion {
  int depth = 0;
  GeoBounds box;
};
Result<GlobalRegion> chooseGlobalRegion(const GlobalStore& store, const GlobalRegionRequest& request);
Result<HeightGrid> loadGlobalStoreRegion(const GlobalStore& store,
                                         const GlobalRegionRequest& request);

// tellus bench with globe renderers: the truth region, the globe path and the runs (reports
// are written by the caller as for flat benches).
Result<std::vector<PathRun>> runGlobeBench(const BenchPathOptions& options,
                                           const PathRunOptions& runOptions,
                                           const std::vector<BenchEntry>& entries);

}  // namespace tellus::cli
