#include "tellus/lod/globe/globe_store_cut.hpp"

#include <algorithm>
#include <cmath>

#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include "tellus/core/geodesy.hpp"

namespace tellus::globe {

double globeStoreTileErrorM(const GlobalStore& store, GeoTileKey key) {
  const TileRecord* record = store.find(key);
  const double codec = store.metadata().maxErrorM;
  return record ? double(record->stats.geometricErrorM) + codec : codec;
}

Aabb globeTileEcefBounds(GeoTileKey key, double lowestM, double highestM) {
  constexpr int kSteps = 8;
  const GeoBounds b = GlobalTiling::bounds(key);
  glm::dvec3 low(1e300), high(-1e300);
  for (int j = 0; j <= kSteps; ++j) {
    const double lat = (b.southDeg + (b.northDeg - b.southDeg) * j / kSteps) * wgs84::kDegree;
    for (int i = 0; i <= kSteps; ++i) {
      const double lon = (b.westDeg + (b.eastDeg - b.westDeg) * i / kSteps) * wgs84::kDegree;
      for (const double h : {lowestM, highestM}) {
        const glm::dvec3 p = wgs84::geodeticToEcef({lat, lon, h});
        low = glm::min(low, p);
        high = glm::max(high, p);
      }
    }
  }
  // Between lattice points the surface bulges out of their hull by at most the sagitta of an
  // arc of one lattice step (on the largest radius the tile reaches).
  const double stepRad = GlobalTiling::tileSizeDeg(key.depth) / kSteps * wgs84::kDegree;
  const double radius = wgs84::kSemiMajorAxisM + std::max(highestM, 0.0);
  const double sagitta = radius * (1.0 - std::cos(0.5 * stepRad));
  return {low - glm::dvec3(sagitta), high + glm::dvec3(sagitta)};
}

namespace {

double distanceToBox(const glm::dvec3& p, const Aabb& box) {
  const glm::dvec3 outside = glm::max(glm::max(box.min - p, p - box.max), glm::dvec3(0.0));
  return glm::length(outside);
}

struct Candidate {
  GeoTileKey key;
  double errorPx = 0.0;  // projected error; infinite with the eye inside the box
  bool refinable = false;
};

}  // namespace

GlobeStoreCut cutGlobeStore(const GlobalStore& store, const GlobeStoreCutView& view,
                            const GlobeStoreCutOptions& options) {
  GlobeStoreCut cut;
  // Where the camera can see it, a tile is a candidate: kept when within tolerance or final,
  // else replaced by its four children. Depth by depth, so that the tile cap refines the
  // worst errors first wherever they are.
  const auto visible = [&](GeoTileKey key, Candidate& out) {
    const TileRecord* stored = store.find(key);  // null: drawn from its deepest stored ancestor
    const TileRecord* record = stored ? stored : store.find(store.deepestStored(key));
    const double lowest = (record ? double(record->stats.minHeightM) : -11000.0) -
                          options.heightMarginM - options.skirtM;
    const double highest = (record ? double(record->stats.maxHeightM) : 9000.0) + options.heightMarginM;
    const Aabb box = globeTileEcefBounds(key, lowest, highest);
    if (!view.frustum.intersects({box.min - view.eyeEcef, box.max - view.eyeEcef})) return false;
    const double distance = distanceToBox(view.eyeEcef, box);
    const double errorM = globeStoreTileErrorM(store, key);
    out.key = key;
    out.errorPx = distance > 0.0 ? errorM * view.focalPx / distance
                                 : (errorM > 0.0 ? INFINITY : 0.0);
    out.refinable = stored && store.hasStoredChildren(key);
    return true;
  };
  std::vector<Candidate> level;
  for (int x = 0; x < GlobalTiling::tilesX(0); ++x) {
    Candidate c;
    if (visible({0, x, 0}, c)) level.push_back(c);
  }
  while (!level.empty()) {
    std::vector<Candidate> refine;
    for (const Candidate& c : level) {
      if (c.refinable && c.errorPx > options.tolerancePx) {
        refine.push_back(c);
      } else {
        cut.tiles.push_back(c.key);
        if (c.refinable) cut.worstErrorPx = std::max(cut.worstErrorPx, c.errorPx);
      }
    }
    // Each refined tile becomes up to four: refine the worst first while the cap allows.
    std::sort(refine.begin(), refine.end(),
              [](const Candidate& a, const Candidate& b) { return a.errorPx > b.errorPx; });
    std::vector<Candidate> next;
    for (std::size_t i = 0; i < refine.size(); ++i) {
      const std::size_t pending = cut.tiles.size() + next.size() + (refine.size() - i);
      if (pending + 3 > options.maxTiles) {
        cut.tiles.push_back(refine[i].key);
        cut.worstErrorPx = std::max(cut.worstErrorPx, refine[i].errorPx);
        ++cut.capped;
        continue;
      }
      for (const GeoTileKey child : GlobalTiling::children(refine[i].key)) {
        Candidate c;
        if (visible(child, c)) next.push_back(c);
      }
    }
    level = std::move(next);
  }
  return cut;
}

}  // namespace tellus::globe
