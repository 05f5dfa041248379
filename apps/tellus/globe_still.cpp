#include "globe_still.hpp"

#include <spdlog/spdlog.h>

#include "global_store_cli.hpp"
#include "tellus/render/globe/globe_reference_renderer.hpp"
#include "tellus/tiles/global_store.hpp"

namespace tellus::cli {

Result<HeightGrid> loadGlobalStoreView(const GlobalStore& store, const std::string& name,
                                       int storeDepth, const std::string& region,
                                       const std::optional<GeoCamera>& camera, double aspect,
                                       std::uint64_t maxSamples) {
  Result<GlobalRegionRequest> made =
      regionRequest(storeDepth, region, camera, aspect,
                    maxSamples > 0 ? maxSamples : GlobalRegionRequest{}.maxSamples);
  if (!made) return made.error();
  const GlobalRegionRequest& request = made.value();
  Result<GlobalRegion> chosen = chooseGlobalRegion(store, request);
  if (!chosen) return chosen.error();
  spdlog::info("drawing depth {} of '{}' over {:.3f}..{:.3f} E, {:.3f}..{:.3f} N", chosen->depth,
               name, chosen->box.westDeg, chosen->box.eastDeg, chosen->box.southDeg,
               chosen->box.northDeg);
  return loadGlobalStoreRegion(store, request);
}

Result<RgbImage> renderGlobeStill(TerrainRenderer& renderer, const GeoCamera& camera,
                                  SnapshotOptions snapshot, FrameStats* stats) {
  const auto* globeRenderer = dynamic_cast<const GlobeReferenceRenderer*>(&renderer);
  const double highest = globeRenderer ? globeRenderer->highestM() : 9000.0;
  const ViewSetup view = geoViewSetup(camera, chooseGeoClipRange(camera, highest, highest),
                                      snapshot.width, snapshot.height);
  snapshot.settings.sky = true;  // the atmosphere behind the globe
  return renderSnapshot(renderer, view, snapshot, stats);
}

}  // namespace tellus::cli
