#pragma once
// Stills on the globe, shared by `tellus render` and `tellus demo`: the part of a global store a
// camera sees, and the picture a globe renderer draws of it.
#include <cstdint>
#include <optional>
#include <string>

#include "tellus/core/geo_camera.hpp"
#include "tellus/core/result.hpp"
#include "tellus/dem/height_grid.hpp"
#include "tellus/render/output/snapshot.hpp"
#include "tellus/render/terrain_renderer.hpp"

namespace tellus {
class GlobalStore;
}

namespace tellus::cli {

// The part of an open global store a globe view draws as one region: `storeDepth` (>= 0) and
// `region` ("W,S,E,N") when given, else what `camera` sees (aspect = width / height) at the
// deepest depth whose samples there number at most `maxSamples` (0: the default budget,
// GlobalRegionRequest::maxSamples). Logs the depth and box chosen under `name`.
Result<HeightGrid> loadGlobalStoreView(const GlobalStore& store, const std::string& name,
                                       int storeDepth, const std::string& region,
                                       const std::optional<GeoCamera>& camera, double aspect,
                                       std::uint64_t maxSamples = 0);

// What `renderer` (a globe renderer) draws from `camera`: the clip range from its highest
// terrain, the atmosphere behind the globe (snapshot.settings.sky is set).
Result<RgbImage> renderGlobeStill(TerrainRenderer& renderer, const GeoCamera& camera,
                                  SnapshotOptions snapshot, FrameStats* stats);

}  // namespace tellus::cli
