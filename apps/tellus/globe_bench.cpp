// tellus bench on the globe: globe renderers along globe camera paths (geo_camera_path.hpp),
// measured against the globe reference's surface (globe_surface.hpp).
#include <algorithm>
#include <cmath>
#include <map>

#include <spdlog/spdlog.h>

#include "cli_support.hpp"
#include "global_store_cli.hpp"
#include "tellus/core/progress.hpp"
#include "tellus/dem/geoid.hpp"
#include "tellus/eval/geo_camera_path.hpp"
#include "tellus/eval/globe_surface.hpp"
#include "tellus/render/registry/renderer_registry.hpp"
#include "tellus/eval/store_surface.hpp"

namespace tellus::cli {
namespace {

// Heights of a global store at any point (its deepest stored tile there), for planning a
// path: the highest of the surfaces a renderer may draw in that cell, ellipsoidal with the
// geoid.
class StoreGround {
 public:
  StoreGround(const GlobalStore& store, const Geoid* geoid) : store_(store), geoid_(geoid) {}
  double operator()(double latDeg, double lonDeg) {
    const int deepest = store_.metadata().deepestDepth;
    const GeoTileKey key = store_.deepestStored(GlobalTiling::tileAt(deepest, latDeg, lonDeg));
    auto it = tiles_.find(key);
    if (it == tiles_.end()) {
      std::vector<float> h(store_.tileShape().sampleCount());
      if (!store_.readTileMetres(key, h)) return std::nan("");
      it = tiles_.emplace(key, std::move(h)).first;
    }
    const int n = store_.tileCells();
    const GeoBounds b = GlobalTiling::bounds(key);
    const double step = GlobalTiling::tileSizeDeg(key.depth) / n;
    double lon = std::fmod(lonDeg - b.westDeg + 720.0, 360.0);
    const double u = std::clamp(lon / step, 0.0, double(n)), v = std::clamp((b.northDeg - latDeg) / step, 0.0, double(n));
    const int i = std::min(int(u), n - 1), j = std::min(int(v), n - 1);
    const auto at = [&](int a, int c) { return double(it->second[std::size_t(c * (n + 1) + a)]); };
    const double fu = u - i, fv = v - j;
    const double nw = at(i, j), ne = at(i + 1, j), sw = at(i, j + 1), se = at(i + 1, j + 1);
    const double top = nw + (ne - nw) * fu, bottom = sw + (se - sw) * fu;
    const double bilinear = top + (bottom - top) * fv;
    // The highest of the surfaces a renderer may draw there (bilinear and both diagonals), so
    // that a camera 2 m above it is above whatever is drawn.
    const double neSw = fu + fv <= 1.0 ? nw + (ne - nw) * fu + (sw - nw) * fv
                                       : se + (sw - se) * (1.0 - fu) + (ne - se) * (1.0 - fv);
    const double nwSe = fu >= fv ? nw + (ne - nw) * fu + (se - ne) * fv
                                 : nw + (sw - nw) * fv + (se - sw) * fu;
    return std::max({bilinear, neSw, nwSe}) +
           (geoid_ ? geoid_->undulationM(latDeg, lonDeg) : 0.0);
  }

 private:
  const GlobalStore& store_;
  const Geoid* geoid_;
  std::map<GeoTileKey, std::vector<float>> tiles_;
};

// The default target: the highest sample of the store's deepest tiles (the finest data's
// summit: the Hida mountains in the ETOPO5 + SRTM store).
Result<GeoPathTarget> highestDeepPoint(const GlobalStore& store) {
  const TileRecord* best = nullptr;
  for (const TileRecord& r : store.records()) {
    if (r.key.level == store.metadata().deepestDepth &&
        (!best || r.stats.maxHeightM > best->stats.maxHeightM)) {
      best = &r;
    }
  }
  const GeoTileKey key = GlobalStore::toGeoKey(best->key);
  std::vector<float> h(store.tileShape().sampleCount());
  if (Status s = store.readTileMetres(key, h); !s) return s.error();
  const std::size_t top = std::size_t(std::max_element(h.begin(), h.end()) - h.begin());
  const int n = store.tileCells();
  return GeoPathTarget{GlobalTiling::sampleLatDeg(key, n, int(top) / (n + 1)),
                       GlobalTiling::sampleLonDeg(key, n, int(top) % (n + 1))};
}

GeoPathTarget highestSample(const HeightGrid& grid) {
  int bx = 0, by = 0;
  for (int y = 0; y < grid.height; ++y) {
    for (int x = 0; x < grid.width; ++x) {
      if (grid.at(x, y) > grid.at(bx, by)) bx = x, by = y;
    }
  }
  const auto& gt = grid.georef.geoTransform;
  return {gt[3] + (by + 0.5) * gt[5], gt[0] + (bx + 0.5) * gt[1]};
}

Result<GeoPathTarget> parseTarget(const std::string& text) {
  Result<GeoCamera> parsed = parseGeoCamera(text + ",0,0,0,45");
  if (!parsed) return makeError("--target '{}' is not LAT,LON in degrees", text);
  return GeoPathTarget{parsed->latDeg, parsed->lonDeg};
}

}  // namespace

Result<std::vector<PathRun>> runGlobeBench(const BenchPathOptions& o, const PathRunOptions& given,
                                           const std::vector<BenchEntry>& entries) {
  std::optional<Geoid> geoid;
  if (!o.geoid.empty()) {
    Result<Geoid> loaded = Geoid::load(o.geoid);
    if (!loaded) return loaded.error();
    geoid = std::move(loaded.value());
  }
  const Geoid* geoidPtr = geoid ? &*geoid : nullptr;
  std::optional<GeoPathTarget> target;
  if (!o.target.empty()) {
    Result<GeoPathTarget> parsed = parseTarget(o.target);
    if (!parsed) return parsed.error();
    target = parsed.value();
  }

  // The path, and the truth it is measured against: a global store (its finest depth wherever
  // a pixel lands, store_surface.hpp), or a latitude/longitude DEM whole.
  std::vector<GeoCamera> cameras;
  double pathSeconds = 0.0;  // the path's duration
  std::shared_ptr<GlobalStore> globalStore;  // every renderer reads it, the reference too
  std::optional<StoreSurface> storeSurface;
  HeightGrid dem;                        // or the DEM, which the renderers draw from
  std::optional<GlobeSurface> demSurface;
  double highestM = 0.0;  // the highest ground (with the geoid's undulation), for clip ranges
  if (o.dem.classified().kind == TerrainInputKind::GlobalStore) {
    Result<std::shared_ptr<GlobalStore>> store = openGlobalStoreInput(o.dem);
    if (!store) return store.error();
    globalStore = store.value();
    if (!target) {
      Result<GeoPathTarget> highest = highestDeepPoint(*store.value());
      if (!highest) return highest.error();
      target = highest.value();
    }
    StoreGround ground(*store.value(), geoidPtr);
    Result<GeoCameraPath> path = makeGeoCameraPath(
        o.path, [&](double lat, double lon) { return ground(lat, lon); }, *target);
    if (!path) return path.error();
    pathSeconds = path->keyframes().back().timeS - path->keyframes().front().timeS;
    cameras = path->sample(framesAlong(o, pathSeconds));
    highestM = double(globalStore->metadata().maxHeightM) + (geoidPtr ? 90.0 : 0.0);
    storeSurface.emplace(globalStore, geoidPtr);
    spdlog::info("globe truth: the store's depth {} everywhere", storeSurface->depth());
  } else {
    Result<HeightGrid> loaded = loadDemInputs(o.dem, rendererBytesPerSample("globe-reference"));
    if (!loaded) return loaded.error();
    if (!loaded->georef.isGeographic || !loaded->georef.hasGeoTransform) {
      return makeError("globe renderers need a global store or a DEM in latitude/longitude");
    }
    if (!target) target = highestSample(loaded.value());
    dem = std::move(loaded.value());
    demSurface.emplace(dem, geoidPtr);
    Result<GeoCameraPath> path = makeGeoCameraPath(
        o.path, [&](double lat, double lon) { return demSurface->ellipsoidalHeightM(lat, lon); },
        *target);
    if (!path) return path.error();
    pathSeconds = path->keyframes().back().timeS - path->keyframes().front().timeS;
    cameras = path->sample(framesAlong(o, pathSeconds));
    highestM = demSurface->highestM();
  }
  const PathRunOptions options = timedAlong(given, pathSeconds, int(cameras.size()));
  std::vector<ViewSetup> views;
  for (const GeoCamera& c : cameras) {
    double ground = storeSurface ? storeSurface->ellipsoidalHeightM(c.latDeg, c.lonDeg)
                                 : demSurface->ellipsoidalHeightM(c.latDeg, c.lonDeg);
    if (!std::isfinite(ground)) ground = 0.0;
    views.push_back(geoViewSetup(c, chooseGeoClipRange(c, ground, highestM), options.width,
                                 options.height));
  }
  PathTruth truth;
  truth.surface = storeSurface ? storeSurface->truth() : demSurface->truth();

  std::vector<BenchEntry> order = entries;
  std::stable_partition(order.begin(), order.end(),
                        [](const BenchEntry& e) { return e.algo == "globe-reference"; });
  // Cracks are judged against the reference's coverage: without the reference in the list, it
  // is drawn first for its coverage alone (a renderer's own coverage shows none of its holes).
  const bool coverageOnly = options.quality && order.front().algo != "globe-reference";
  if (coverageOnly) order.insert(order.begin(), BenchEntry{"globe-reference", "globe-reference", o.renderers});
  std::vector<PathRun> runs;
  CoverageMasks referenceCoverage;
  for (const BenchEntry& entry : order) {
    const std::string& algo = entry.algo;
    Progress progress(coverageOnly && algo == "globe-reference" ? std::string("reference coverage")
                                                                : fmt::format("bench {}", entry.label),
                      cameras.size());
    if (rendererNeedsGlobalStore(algo) && !globalStore) {
      return makeError("renderer '{}' streams from a global store: give one built with "
                       "'tellus build --global'",
                       algo);
    }
    // On a store every renderer reads the store itself (the reference its cut of the finest
    // tiles, the others their own level of detail); on a DEM they draw the grid.
    RendererInputs inputs;
    inputs.globalStore = globalStore;
    inputs.grid = globalStore ? nullptr : &dem;
    inputs.geoid = geoidPtr;
    inputs.waitForTiles = o.settle;
    Result<std::unique_ptr<TerrainRenderer>> made = makeRenderer(algo, inputs, entry.settings);
    if (!made) return made.error();
    PathRunOptions runOptions = options;
    if (coverageOnly && algo == "globe-reference") runOptions.frameSink = nullptr;  // not asked for
    // Each renderer starts with no imagery resident; the reference drawn for coverage needs none.
    Result<std::unique_ptr<ImageryTextures>> imagery =
        coverageOnly && algo == "globe-reference" ? Result<std::unique_ptr<ImageryTextures>>(nullptr)
                                                  : makeImagery(o.imagery, nullptr, o.dem.inputs.front());
    if (!imagery) return imagery.error();
    runOptions.settings.imagery = imagery->get();
    Result<PathRun> run = runViews(*made.value(), views, truth, runOptions, referenceCoverage,
                                   [&](int) { progress.advance(); });
    if (!run) return run.error();
    PathRun whole = std::move(run.value());
    if (options.quality && algo == "globe-reference") referenceCoverage = whole.coverage;
    whole.coverage.clear();
    for (std::size_t i = 0; i < whole.frames.size(); ++i) whole.frames[i].geoCamera = cameras[i];
    if (coverageOnly && algo == "globe-reference") continue;  // drawn for its coverage only
    whole.algo = entry.label;
    runs.push_back(std::move(whole));
  }
  return runs;
}

}  // namespace tellus::cli
