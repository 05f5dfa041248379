#include "global_store_cli.hpp"


#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "cli_support.hpp"
#include "tellus/core/geodesy.hpp"
#include "tellus/core/memory_budget.hpp"
#include "tellus/core/progress.hpp"

namespace tellus::cli {
namespace {

// Terrain beyond the horizon that the camera-chosen region still includes: peaks up to this
// height rise into view from behind it.
constexpr double kBeyondHorizonTerrainM = 2000.0;

std::string describeBox(const GeoBounds& b) {
  return fmt::format("{:.4f}..{:.4f} E, {:.4f}..{:.4f} N", b.westDeg, b.eastDeg, b.southDeg,
                     b.northDeg);
}

// What verify finds wrong with one tile, empty when nothing.
std::string checkGlobalTile(const GlobalStore& store, const TileRecord& record) {
  const GeoTileKey key = GlobalStore::toGeoKey(record.key);
  const int n = store.tileCells(), side = n + 1;
  const std::string name = store.path().string();
  const auto read = [&](GeoTileKey k, std::vector<float>& h) -> Status {
    h.resize(store.tileShape().sampleCount());
    return store.readTileMetres(k, h);
  };
  std::vector<float> h, other;
  if (Status s = read(key, h); !s) return s.error().message;
  const GlobalStoreMetadata& m = store.metadata();
  const auto [lo, hi] = std::minmax_element(h.begin(), h.end());
  if (*lo != record.stats.minHeightM || *hi != record.stats.maxHeightM) {
    return fmt::format("'{}': {} decodes to heights {}..{} m but its index says {}..{} m", name,
                       GlobalStore::describe(key), *lo, *hi, record.stats.minHeightM,
                       record.stats.maxHeightM);
  }
  const auto at = [&](const std::vector<float>& t, int i, int j) {
    return t[std::size_t(j) * std::size_t(side) + std::size_t(i)];
  };
  // Pole rows.
  for (int i = 0; i <= n; ++i) {
    if ((key.y == 0 && at(h, i, 0) != m.northPoleM) ||
        (key.y == GlobalTiling::tilesY(key.depth) - 1 && at(h, i, n) != m.southPoleM)) {
      return fmt::format("'{}': {} has a pole sample that is not the pole's height", name,
                         GlobalStore::describe(key));
    }
  }
  // Edges shared with the stored eastern and southern neighbours.
  const GeoNeighbour east = GlobalTiling::neighbour(key, GeoSide::East);
  if (store.find(east.key)) {
    if (Status s = read(east.key, other); !s) return s.error().message;
    for (int j = 0; j <= n; ++j) {
      if (at(h, n, j) != at(other, 0, j)) {
        return fmt::format("'{}': {} and its eastern neighbour differ on their shared edge "
                           "(row {}: {} m vs {} m)",
                           name, GlobalStore::describe(key), j, at(h, n, j), at(other, 0, j));
      }
    }
  }
  if (key.y + 1 < GlobalTiling::tilesY(key.depth)) {
    const GeoTileKey south{key.depth, key.x, key.y + 1};
    if (store.find(south)) {
      if (Status s = read(south, other); !s) return s.error().message;
      for (int i = 0; i <= n; ++i) {
        if (at(h, i, n) != at(other, i, 0)) {
          return fmt::format("'{}': {} and its southern neighbour differ on their shared edge "
                             "(column {}: {} m vs {} m)",
                             name, GlobalStore::describe(key), i, at(h, i, n), at(other, i, 0));
        }
      }
    }
  }
  // Nesting with the parent, and the parent's error bounding this tile's deviation.
  if (key.depth > 0) {
    const GeoTileKey parent = GlobalTiling::parent(key);
    if (Status s = read(parent, other); !s) return s.error().message;
    const int ox = (key.x % 2) * n / 2, oy = (key.y % 2) * n / 2;
    float deviation = 0.0f;
    for (int j = 0; j <= n; ++j) {
      for (int i = 0; i <= n; ++i) {
        const double surface = tileSurfaceAt(other, n, ox + 0.5 * i, oy + 0.5 * j);
        deviation = std::max(deviation, float(std::abs(at(h, i, j) - surface)));
        if (i % 2 == 0 && j % 2 == 0 && at(h, i, j) != at(other, ox + i / 2, oy + j / 2)) {
          return fmt::format("'{}': {} sample ({}, {}) is {} m, its parent holds {} m there", name,
                             GlobalStore::describe(key), i, j, at(h, i, j),
                             at(other, ox + i / 2, oy + j / 2));
        }
      }
    }
    const TileRecord* parentRecord = store.find(parent);
    if (parentRecord->stats.geometricErrorM < deviation * (1.0f - 1e-6f) - 1e-6f) {
      return fmt::format("'{}': {} deviates {} m from its parent's surface, more than the "
                         "parent's recorded error {} m",
                         name, GlobalStore::describe(key), deviation,
                         parentRecord->stats.geometricErrorM);
    }
  }
  return {};
}

}  // namespace

int printGlobalStoreInfo(const DemInputOptions& input) {
  const std::string& path = input.inputs.at(0);
  Result<std::shared_ptr<GlobalStore>> opened = openGlobalStoreInput(input);
  if (!opened) return fail(opened.error());
  const GlobalStore& store = *opened.value();
  const GlobalStoreMetadata& m = store.metadata();
  const auto row = [](std::string_view name, const std::string& value) {
    fmt::print("{:<18}{}\n", fmt::format("{}:", name), value);
  };
  row("store", fmt::format("{} ({}, global: latitude/longitude quadtree)", path, m.producer));
  row("tiles", fmt::format("{} cells ({} x {} samples), {} tiles, depths 0..{}", m.tileCells,
                           m.tileCells + 1, m.tileCells + 1, store.records().size(),
                           m.deepestDepth));
  row("heights", fmt::format("min {:.2f} m, max {:.2f} m (above the geoid as the sources give "
                             "them; quantum {} m)",
                             m.minHeightM, m.maxHeightM, m.quantumM));
  row("poles", fmt::format("north {:.2f} m, south {:.2f} m", m.northPoleM, m.southPoleM));
  row("codec", m.maxErrorSteps == 0
                   ? fmt::format("{} (lossless; rounding to the quantum moved heights by at "
                                 "most {} m)",
                                 m.codec, m.maxErrorM)
                   : fmt::format("{} (max error {} m)", m.codec, m.maxErrorM));
  row("uncovered", m.uncoveredSamples == 0
                       ? std::string("none (every sample comes from a source)")
                       : fmt::format("{} samples outside every source, stored at 0 m",
                                     m.uncoveredSamples));
  row("sea", m.zeroYieldsToSeaFloor
                 ? std::string("a source's 0 m samples yield to a coarser source's sea floor")
                 : std::string("every source's 0 m samples kept (--zero-is-land)"));
  row("edges", m.edgeBlendM > 0.0
                   ? fmt::format("each source that does not cover the globe fades into the "
                                 "coarser ones over {:g} m inside its edges (--blend-edges)",
                                 m.edgeBlendM)
                   : std::string("each source's values up to its edge (no --blend-edges)"));
  std::uint64_t payload = 0;
  for (const TileRecord& r : store.records()) payload += r.payloadBytes;
  const double samples = double(store.records().size()) * double(store.tileShape().sampleCount());
  row("size", fmt::format("{} file, {} of tiles: {:.2f} bits/sample", formatByteCount(double(store.fileBytes())),
                          formatByteCount(double(payload)), 8.0 * double(payload) / samples));
  if (m.buildSeconds > 0.0) row("built in", fmt::format("{:.1f} s", m.buildSeconds));
  fmt::print("\nsources, finest first (a sample takes the first that has data there{}):\n",
             m.edgeBlendM > 0.0 ? "; near a source's edges, a blend with the next" : "");
  for (const GlobalStoreSource& s : m.sources) {
    fmt::print("  {}: {}, spacing {:.2f}\" , feeds depths 0..{}\n", s.path, describeBox(s.bounds),
               s.spacingDeg * 3600.0, s.depth);
  }
  fmt::print("\n{:>5} {:>9} {:>10} {:>12} {:>12} {:>12}\n", "depth", "tiles", "spacing",
             "bytes", "bytes/tile", "max error m");
  for (int d = 0; d <= m.deepestDepth; ++d) {
    std::uint64_t bytes = 0;
    float worst = 0.0f;
    std::size_t count = 0;
    for (const TileRecord& r : store.records()) {
      if (r.key.level != d) continue;
      bytes += r.payloadBytes;
      worst = std::max(worst, r.stats.geometricErrorM);
      ++count;
    }
    const double spacingDeg = GlobalTiling::tileSizeDeg(d) / m.tileCells;
    fmt::print("{:>5} {:>9} {:>9.2f}\" {:>12} {:>12.0f} {:>12.2f}\n", d, count,
               spacingDeg * 3600.0, formatByteCount(double(bytes)),
               double(bytes) / double(std::max<std::size_t>(count, 1)), worst);
  }
  return 0;
}

int verifyGlobalStore(const DemInputOptions& input) {
  const std::string& path = input.inputs.at(0);
  Result<std::shared_ptr<GlobalStore>> opened = openGlobalStoreInput(input);
  if (!opened) return fail(opened.error());
  const GlobalStore& store = *opened.value();
  return checkEveryTile(path, store.records(),
                        [&](const TileRecord& r) { return checkGlobalTile(store, r); },
                        " (checksums, index, shared edges, nesting, poles)", store.source());
}

Result<GeoBounds> parseGeoBounds(const std::string& text) {
  double v[4] = {};
  int count = 0;
  std::size_t start = 0;
  while (count < 4) {
    const std::size_t comma = text.find(',', start);
    const std::string part = text.substr(start, comma == std::string::npos ? std::string::npos
                                                                           : comma - start);
    char* end = nullptr;
    v[count] = std::strtod(part.c_str(), &end);
    if (part.empty() || end != part.c_str() + part.size() || !std::isfinite(v[count])) {
      return makeError("region '{}' is not WEST,SOUTH,EAST,NORTH in degrees", text);
    }
    ++count;
    if (comma == std::string::npos) break;
    start = comma + 1;
  }
  if (count != 4 || text.find(',', start) != std::string::npos) {
    return makeError("region '{}' is not WEST,SOUTH,EAST,NORTH in degrees", text);
  }
  const GeoBounds b{v[0], v[1], v[2], v[3]};
  if (!(b.westDeg >= -180.0 && b.eastDeg <= 180.0 && b.westDeg < b.eastDeg &&
        b.southDeg >= -90.0 && b.northDeg <= 90.0 && b.southDeg < b.northDeg)) {
    return makeError("region '{}': need -180 <= west < east <= 180 and -90 <= south < north <= 90",
                     text);
  }
  return b;
}

namespace {

// The ground a camera's view can show (geoViewFootprint), as a region.
GeoBounds footprintBox(const GeoCamera& camera, double aspect) {
  const GeoFootprint f = geoViewFootprint(camera, aspect, kBeyondHorizonTerrainM);
  return {f.westDeg, f.southDeg, f.eastDeg, f.northDeg};
}

std::uint64_t regionSamples(const GlobalStore& store, int depth, const GeoBounds& b) {
  const double step = GlobalTiling::tileSizeDeg(depth) / store.tileCells();
  return std::uint64_t((b.eastDeg - b.westDeg) / step + 2.0) *
         std::uint64_t((b.northDeg - b.southDeg) / step + 2.0);
}

}  // namespace

Result<GlobalRegionRequest> regionRequest(int storeDepth, const std::string& region,
                                          const std::optional<GeoCamera>& camera, double aspect,
                                          std::uint64_t maxSamples) {
  GlobalRegionRequest request;
  if (storeDepth >= 0) request.depth = storeDepth;
  if (!region.empty()) {
    Result<GeoBounds> parsed = parseGeoBounds(region);
    if (!parsed) return parsed.error();
    request.region = parsed.value();
  }
  request.camera = camera;
  request.aspect = aspect;
  request.maxSamples = maxSamples;
  return request;
}

Result<GlobalRegion> chooseGlobalRegion(const GlobalStore& store,
                                        const GlobalRegionRequest& request) {
  GlobalRegion region;
  region.box = request.region ? *request.region
               : request.camera ? footprintBox(*request.camera, request.aspect)
                                : GeoBounds{-180.0, -90.0, 180.0, 90.0};
  const int deepest = store.metadata().deepestDepth;
  if (request.depth) {
    if (*request.depth > deepest) {
      return makeError("'{}' has depths 0..{}, not {}", store.path().string(), deepest,
                       *request.depth);
    }
    region.depth = *request.depth;
    return region;
  }
  // The deepest depth stored under the camera (or anywhere in the region), made shallower
  // until the region fits the sample budget.
  int depth = deepest;
  if (request.camera) {
    const GeoTileKey under = GlobalTiling::tileAt(deepest, request.camera->latDeg,
                                                  request.camera->lonDeg);
    depth = store.deepestStored(under).depth;
  }
  while (depth > 0 && regionSamples(store, depth, region.box) > request.maxSamples) --depth;
  region.depth = depth;
  return region;
}

Result<HeightGrid> loadGlobalStoreRegion(const GlobalStore& store,
                                         const GlobalRegionRequest& request) {
  Result<GlobalRegion> region = chooseGlobalRegion(store, request);
  if (!region) return region.error();
  // An explicit depth may exceed the budget (up to what readGlobalRegion takes); a chosen one
  // fits it, except at depth 0.
  const std::uint64_t limit =
      request.depth ? std::uint64_t(1) << 28
                    : std::max(request.maxSamples, regionSamples(store, region->depth, region->box));
  return readGlobalRegion(store, region->depth, region->box, limit);
}

}  // namespace tellus::cli
