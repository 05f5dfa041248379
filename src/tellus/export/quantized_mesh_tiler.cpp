#include "tellus/export/quantized_mesh_tiler.hpp"

#include <sys/statvfs.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <optional>
#include <mutex>
#include <numbers>

#include <fmt/format.h>
#include <glm/geometric.hpp>
#include <nlohmann/json.hpp>
#include <tbb/parallel_for.h>

#include "tellus/core/atomic_output.hpp"
#include "tellus/core/folder_output.hpp"
#include "tellus/core/memory_budget.hpp"
#include "tellus/core/geodesy.hpp"
#include "tellus/export/lonlat_sampler.hpp"
#include "tellus/export/quantized_mesh.hpp"
#include "tellus/export/terrain_mesh.hpp"

namespace tellus {
namespace fs = std::filesystem;

double cesiumGeometricErrorM(int level) {
  const double levelZero = wgs84::kSemiMajorAxisM * 2.0 * std::numbers::pi * 0.25 / (65.0 * 2.0);
  return std::ldexp(levelZero, -level);
}

namespace {

struct TileRange {
  int x0 = 0, y0 = 0, x1 = -1, y1 = -1;  // inclusive
  std::uint64_t count() const { return std::uint64_t(x1 - x0 + 1) * std::uint64_t(y1 - y0 + 1); }
};

double tileExtentDeg(int level) { return std::ldexp(180.0, -level); }

// Tiles of `level` that touch the data's box (level 0: both, as Cesium needs its roots).
TileRange tilesCovering(const LonLatBox& box, int level) {
  if (level == 0) return {0, 0, 1, 0};
  const double extent = tileExtentDeg(level);
  const int tilesX = 2 << level, tilesY = 1 << level;
  auto index = [&](double value, double origin, int count) {
    return std::clamp(int(std::floor((value - origin) / extent)), 0, count - 1);
  };
  return {index(box.westDeg, -180.0, tilesX), index(box.southDeg, -90.0, tilesY),
          index(box.eastDeg, -180.0, tilesX), index(box.northDeg, -90.0, tilesY)};
}

struct TileResult {
  std::uint64_t bytes = 0;
  std::uint64_t triangles = 0;
  double errorM = 0.0;
};

// One tile: the lattice's heights, the simplified mesh, its quantized-mesh bytes.
Result<std::vector<std::byte>> makeTile(const LonLatSampler& sampler, const Geoid* geoid,
                                        int level, int x, int y, int n, TileResult& result) {
  const double extent = tileExtentDeg(level);
  const double west = -180.0 + x * extent, south = -90.0 + y * extent;
  // The lattice with one more sample beyond each edge (for the normals' differences): m x m,
  // lattice sample (i, j) of the tile at (i + 1, j + 1); edges computed exactly so that
  // neighbouring tiles sample the same points.
  const int m = n + 2;
  auto coordinate = [&](double origin, int index) {
    return index == n - 1 ? origin + extent : origin + extent * index / (n - 1);
  };
  std::vector<double> lons(std::size_t(m) * std::size_t(m)), lats(lons.size());
  for (int j = 0; j < m; ++j) {
    for (int i = 0; i < m; ++i) {
      lons[std::size_t(j * m + i)] = coordinate(west, i - 1);
      lats[std::size_t(j * m + i)] = std::clamp(coordinate(south, j - 1), -90.0, 90.0);
    }
  }
  std::vector<float> extended(lons.size());
  sampler.sample(lons, lats, extended);
  for (std::size_t k = 0; k < extended.size(); ++k) {
    if (!std::isfinite(extended[k])) extended[k] = 0.0f;  // outside the data: the geoid
    if (geoid) extended[k] = float(geoid->ellipsoidalHeightM(extended[k], lats[k], lons[k]));
  }
  std::vector<float> heights(std::size_t(n) * std::size_t(n));
  for (int j = 0; j < n; ++j) {
    std::copy_n(&extended[std::size_t((j + 1) * m + 1)], n, &heights[std::size_t(j * n)]);
  }
  // The data's own normal at lattice sample (col, row) of the tile: central differences over
  // the extended lattice in the local east-north-up frame, taken to ECEF. Shared border
  // samples get the same normal in both tiles: no shading seam between tiles.
  const double stepRad = extent / (n - 1) * wgs84::kDegree;
  auto dataNormal = [&](int col, int row) {
    const std::size_t centre = std::size_t((row + 1) * m + col + 1);
    const double latRad = lats[centre] * wgs84::kDegree, lonRad = lons[centre] * wgs84::kDegree;
    const double dx = std::max(2.0 * wgs84::eastWestMetres(latRad, stepRad), 1e-3);
    const double dy = 2.0 * wgs84::northSouthMetres(latRad, stepRad);
    const double dhdx = (double(extended[centre + 1]) - double(extended[centre - 1])) / dx;
    const double dhdy = (double(extended[centre + std::size_t(m)]) - double(extended[centre - std::size_t(m)])) / dy;
    const glm::dvec3 east(-std::sin(lonRad), std::cos(lonRad), 0.0);
    const glm::dvec3 north(-std::sin(latRad) * std::cos(lonRad), -std::sin(latRad) * std::sin(lonRad), std::cos(latRad));
    const glm::dvec3 up(std::cos(latRad) * std::cos(lonRad), std::cos(latRad) * std::sin(lonRad), std::sin(latRad));
    return glm::normalize(-dhdx * east - dhdy * north + up);
  };
  auto latticeLat = [&](std::uint32_t sample) { return lats[std::size_t((sample / std::uint32_t(n) + 1) * std::uint32_t(m) + sample % std::uint32_t(n) + 1)]; };
  auto latticeLon = [&](std::uint32_t sample) { return lons[std::size_t((sample / std::uint32_t(n) + 1) * std::uint32_t(m) + sample % std::uint32_t(n) + 1)]; };

  const double midLatRad = (south + 0.5 * extent) * wgs84::kDegree;
  GridHeights grid;
  grid.width = grid.height = n;
  grid.spacingXM = wgs84::eastWestMetres(midLatRad, extent * wgs84::kDegree) / (n - 1);
  grid.spacingYM = wgs84::northSouthMetres(midLatRad, extent * wgs84::kDegree) / (n - 1);
  grid.heightsM = heights;
  Result<TerrainMesh> built =
      buildTerrainMesh(grid, {.maxErrorM = cesiumGeometricErrorM(level), .lockBorder = true});
  if (!built) return built.error();
  TerrainMesh& mesh = built.value();
  orderForRendering(mesh);  // first-use order: high-water-mark coding
  const std::vector<std::uint32_t>& samples = mesh.samples;

  QuantizedMeshTile tile;
  const std::size_t count = samples.size();
  float minH = heights[samples[0]], maxH = minH;
  for (const std::uint32_t s : samples) {
    minH = std::min(minH, heights[s]);
    maxH = std::max(maxH, heights[s]);
  }
  tile.u.resize(count);
  tile.v.resize(count);
  tile.height.resize(count);
  std::vector<glm::dvec3> ecef(count);
  glm::dvec3 lo(std::numeric_limits<double>::max()), hi(-std::numeric_limits<double>::max());
  for (std::size_t k = 0; k < count; ++k) {
    const int col = int(samples[k]) % n, row = int(samples[k]) / n;
    tile.u[k] = std::uint16_t(std::lround(double(col) / (n - 1) * kQuantizedMeshMaxCoordinate));
    tile.v[k] = std::uint16_t(std::lround(double(row) / (n - 1) * kQuantizedMeshMaxCoordinate));
    const float h = heights[samples[k]];
    tile.height[k] = maxH > minH ? std::uint16_t(std::lround(double(h - minH) / double(maxH - minH) *
                                                              kQuantizedMeshMaxCoordinate))
                                 : 0;
    if (col == 0) tile.westEdge.push_back(std::uint32_t(k));
    if (row == 0) tile.southEdge.push_back(std::uint32_t(k));
    if (col == n - 1) tile.eastEdge.push_back(std::uint32_t(k));
    if (row == n - 1) tile.northEdge.push_back(std::uint32_t(k));
    ecef[k] = wgs84::geodeticToEcef({latticeLat(samples[k]) * wgs84::kDegree,
                                     latticeLon(samples[k]) * wgs84::kDegree, double(h)});
    lo = glm::min(lo, ecef[k]);
    hi = glm::max(hi, ecef[k]);
  }
  tile.indices = mesh.indices;

  tile.octNormals.resize(count);
  for (std::size_t k = 0; k < count; ++k) {
    tile.octNormals[k] = octEncodeNormal(dataNormal(int(samples[k]) % n, int(samples[k]) / n));
  }

  QuantizedMeshHeader& header = tile.header;
  header.minHeightM = minH;
  header.maxHeightM = maxH;
  header.boundingSphereCentreEcef = 0.5 * (lo + hi);
  header.centreEcef = header.boundingSphereCentreEcef;
  for (const glm::dvec3& p : ecef) {
    header.boundingSphereRadiusM =
        std::max(header.boundingSphereRadiusM, glm::length(p - header.boundingSphereCentreEcef));
  }
  if (!horizonOcclusionPoint(header.centreEcef, ecef, header.horizonOcclusionPoint)) {
    // No finite point hides exactly this tile (it spans too much of the globe): one far out
    // along its centre's direction, hidden only from the far side of the Earth.
    header.horizonOcclusionPoint = glm::normalize(header.centreEcef) * 1e6;
  }
  result.triangles = tile.indices.size() / 3;
  result.errorM = mesh.maxErrorM;
  return encodeQuantizedMesh(tile);
}

// Tiles go into the temporary folder, renamed as a whole at the end.
Status writeFile(const fs::path& path, std::span<const std::byte> bytes) {
  return writeBytesChecked(path, bytes, path);
}

std::string layerJson(const std::vector<TileRange>& ranges, const TileStore& store) {
  nlohmann::json available = nlohmann::json::array();
  for (const TileRange& r : ranges) {
    available.push_back(nlohmann::json::array(
        {{{"startX", r.x0}, {"startY", r.y0}, {"endX", r.x1}, {"endY", r.y1}}}));
  }
  const nlohmann::json layer = {
      {"tilejson", "2.1.0"},
      {"name", store.path().stem().string()},
      {"description", fmt::format("Terrain of {} exported by Tellus", store.path().filename().string())},
      {"version", "1.0.0"},
      {"format", "quantized-mesh-1.0"},
      {"attribution", ""},
      {"scheme", "tms"},
      {"tiles", {"{z}/{x}/{y}.terrain?v={version}"}},
      {"projection", "EPSG:4326"},
      {"bounds", {-180.0, -90.0, 180.0, 90.0}},
      {"minzoom", 0},
      {"maxzoom", int(ranges.size()) - 1},
      {"extensions", {"octvertexnormals"}},
      {"available", available}};
  return layer.dump(1);
}

}  // namespace

FolderOutputKind quantizedMeshFolderKind() {
  FolderOutputKind kind;
  kind.description = "a quantized-mesh tile set";
  kind.markerName = ".tellus-tileset";
  kind.markerContent = "{\"writer\": \"tellus " TELLUS_VERSION "\", \"format\": \"quantized-mesh-1.0\"}\n";
  // layer.json, Z, Z/X and Z/X/Y.terrain.
  kind.ownEntry = [](const fs::path& relative) {
    const auto isNumber = [](const std::string& text) {
      return !text.empty() && text.size() <= 10 &&
             std::all_of(text.begin(), text.end(), [](char c) { return c >= '0' && c <= '9'; });
    };
    std::vector<std::string> parts;
    for (const fs::path& part : relative) parts.push_back(part.string());
    if (parts.size() == 1 && parts[0] == "layer.json") return true;
    if (parts.empty() || parts.size() > 3) return false;
    for (std::size_t k = 0; k + 1 < parts.size(); ++k) {
      if (!isNumber(parts[k])) return false;
    }
    const std::string& last = parts.back();
    if (parts.size() < 3) return isNumber(last);
    return last.size() > 8 && last.ends_with(".terrain") && isNumber(last.substr(0, last.size() - 8));
  };
  return kind;
}

namespace {

// The least a tile set of `tiles` files takes on the file system holding `folder`: a block a
// tile. Refuses, with the figures, a set that cannot fit its free space or free inodes.
Status checkTileSetFits(const fs::path& folder, std::uint64_t tiles, int maxLevel,
                        int naturalMaxLevel) {
  fs::path parent = fs::absolute(folder).lexically_normal();
  if (parent.filename().empty()) parent = parent.parent_path();
  parent = parent.parent_path();
  struct statvfs disk {};
  if (::statvfs(parent.c_str(), &disk) != 0) return {};  // unknown: no refusal
  const double block = double(std::max<unsigned long>(disk.f_frsize, 512));
  const double needBytes = double(tiles) * block;
  const double freeBytes = double(disk.f_bavail) * double(disk.f_frsize);
  const bool inodesKnown = disk.f_files > 0;
  if (needBytes > freeBytes || (inodesKnown && double(tiles) > double(disk.f_favail))) {
    return makeError(
        "a quantized-mesh tile set of levels 0..{} is {} tiles: at least {} and {} files on "
        "disk, more than the {} and {} files free in '{}'; give a smaller --max-level (the "
        "store's samples need no more than level {})",
        maxLevel, tiles, formatByteCount(needBytes), tiles, formatByteCount(freeBytes),
        inodesKnown ? std::to_string(disk.f_favail) : std::string("unknown"), parent.string(),
        naturalMaxLevel);
  }
  return {};
}

// Temporaries of earlier Tellus versions (".NAME.tmp-PID" beside DIR) left by killed exports:
// removed when their process is gone and they hold nothing but a tile set's entries.
void sweepLegacyTemporaries(const fs::path& folder, const FolderOutputKind& kind) {
  fs::path absolute = fs::absolute(folder).lexically_normal();
  if (absolute.filename().empty()) absolute = absolute.parent_path();
  const std::string prefix = "." + absolute.filename().string() + ".tmp-";
  std::error_code ec;
  for (const fs::directory_entry& entry : fs::directory_iterator(absolute.parent_path(), ec)) {
    const std::string name = entry.path().filename().string();
    if (!name.starts_with(prefix) || !entry.is_directory(ec) || entry.is_symlink(ec)) continue;
    const std::string digits = name.substr(prefix.size());
    if (digits.empty() || digits.size() > 9 ||
        !std::all_of(digits.begin(), digits.end(), [](char c) { return c >= '0' && c <= '9'; })) {
      continue;
    }
    if (processExists(std::stol(digits))) continue;
    bool tileSet = true;
    for (fs::recursive_directory_iterator it(entry.path(), ec), end; !ec && it != end; it.increment(ec)) {
      if (it->is_symlink() || !kind.ownEntry(it->path().lexically_relative(entry.path()))) {
        tileSet = false;
        break;
      }
    }
    if (tileSet && !ec) fs::remove_all(entry.path(), ec);
  }
}

}  // namespace

Result<QuantizedMeshExportReport> exportQuantizedMesh(const TileStore& store,
                                                      const fs::path& folder,
                                                      const QuantizedMeshExportOptions& options) {
  if (options.tileSamples < 3 || options.tileSamples > 1025) {
    return makeError("tile lattice of {} samples a side: it must be 3 to 1025", options.tileSamples);
  }
  if (options.maxLevel > 20) {
    return makeError("quantized-mesh level {} is beyond 20 (tiles of 15 cm)", options.maxLevel);
  }
  const FolderOutputKind kind = quantizedMeshFolderKind();
  if (Status writable = checkFolderOutput(folder, kind); !writable) return writable.error();
  const PyramidLayout& layout = store.layout();
  // The finest level's sampler decides the data's box and the default depth.
  Result<HeightGrid> finest = readStoreLevel(store, 0);
  if (!finest) return finest.error();
  Result<LonLatSampler> level0 = LonLatSampler::create(std::move(finest.value()));
  if (!level0) {
    return makeError("'{}': {}", store.path().string(), level0.error().message);
  }
  const LonLatBox box = level0->bounds();
  const int n = options.tileSamples;
  int naturalMaxLevel = 0;
  while (naturalMaxLevel < 20 && tileExtentDeg(naturalMaxLevel) / (n - 1) > level0->spacingDeg()) {
    ++naturalMaxLevel;
  }
  // Levels finer than the data add tiles without detail (Cesium refines the finest level by
  // itself); two beyond it are allowed, for lattices that sample between the store's samples.
  if (options.maxLevel > naturalMaxLevel + kExtraQuantizedMeshLevels) {
    return makeError("--max-level {} is {} levels finer than '{}' needs (level {} already has a "
                     "lattice as fine as its samples): its tiles would add no detail; give at "
                     "most {}",
                     options.maxLevel, options.maxLevel - naturalMaxLevel, store.path().string(),
                     naturalMaxLevel, naturalMaxLevel + kExtraQuantizedMeshLevels);
  }
  const int maxLevel = options.maxLevel < 0 ? naturalMaxLevel : options.maxLevel;
  std::uint64_t totalTiles = 0;
  for (int level = 0; level <= maxLevel; ++level) totalTiles += tilesCovering(box, level).count();
  if (Status fits = checkTileSetFits(folder, totalTiles, maxLevel, naturalMaxLevel); !fits) {
    return fits.error();
  }

  sweepLegacyTemporaries(folder, kind);
  Result<FolderOutput> output = FolderOutput::begin(folder, kind);
  if (!output) return output.error();
  const fs::path temporary = output->temporary();
  std::error_code ec;

  QuantizedMeshExportReport report;
  std::vector<TileRange> ranges;
  std::optional<LonLatSampler> coarser;  // the sampler of the store level in use (not 0)
  int coarserLevel = -1;
  std::atomic<std::uint64_t> tilesDone{0};
  for (int level = 0; level <= maxLevel; ++level) {
    // The coarsest store level whose samples are at least as fine as this lattice.
    const double latticeDeg = tileExtentDeg(level) / (n - 1);
    int storeLevel = 0;
    while (storeLevel + 1 < layout.levelCount() &&
           level0->spacingDeg() * double(PyramidLayout::stride(storeLevel + 1)) <= latticeDeg) {
      ++storeLevel;
    }
    if (storeLevel != 0 && storeLevel != coarserLevel) {
      Result<HeightGrid> grid = readStoreLevel(store, storeLevel);
      if (!grid) return grid.error();
      Result<LonLatSampler> sampler = LonLatSampler::create(std::move(grid.value()));
      if (!sampler) return sampler.error();
      coarser = std::move(sampler.value());
      coarserLevel = storeLevel;
    }
    const LonLatSampler& sampler = storeLevel == 0 ? level0.value() : *coarser;

    const TileRange range = tilesCovering(box, level);
    ranges.push_back(range);
    for (int x = range.x0; x <= range.x1; ++x) {
      fs::create_directories(temporary / std::to_string(level) / std::to_string(x), ec);
      if (ec) return makeError("cannot create a folder in '{}': {}", temporary.string(), ec.message());
    }
    const int columns = range.x1 - range.x0 + 1;
    std::vector<TileResult> results(range.count());
    std::mutex errorMutex;
    std::optional<Error> firstError;
    tbb::parallel_for(std::size_t(0), results.size(), [&](std::size_t k) {
      {
        std::lock_guard lock(errorMutex);
        if (firstError) return;  // stop early: the export has failed
      }
      const int x = range.x0 + int(k % std::size_t(columns));
      const int y = range.y0 + int(k / std::size_t(columns));
      Result<std::vector<std::byte>> bytes = makeTile(sampler, options.geoid, level, x, y, n, results[k]);
      Status written = bytes ? writeFile(temporary / std::to_string(level) / std::to_string(x) /
                                             fmt::format("{}.terrain", y),
                                         bytes.value())
                             : Status(bytes.error());
      if (!written) {
        std::lock_guard lock(errorMutex);
        if (!firstError) firstError = written.error();
        return;
      }
      results[k].bytes = bytes->size();
      const std::uint64_t done = ++tilesDone;
      if (options.progress) options.progress(done, totalTiles);
    });
    if (firstError) return *firstError;
    QuantizedMeshLevelReport levelReport;
    levelReport.level = level;
    levelReport.storeLevel = storeLevel;
    levelReport.geometricErrorM = cesiumGeometricErrorM(level);
    levelReport.tiles = results.size();
    for (const TileResult& r : results) {
      levelReport.bytes += r.bytes;
      levelReport.triangles += r.triangles;
      levelReport.maxErrorM = std::max(levelReport.maxErrorM, r.errorM);
    }
    report.tiles += levelReport.tiles;
    report.bytes += levelReport.bytes;
    report.levels.push_back(levelReport);
  }
  const std::string layer = layerJson(ranges, store);
  if (Status s = writeFile(temporary / "layer.json", std::as_bytes(std::span(layer))); !s) {
    return s.error();
  }
  if (Status s = output->commit(); !s) return s.error();
  return report;
}

}  // namespace tellus
