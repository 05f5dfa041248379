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
#include "tellus/export/quantized_mesh_tile_builder.hpp"

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

double tileExtentDeg(int level) { return quantizedMeshTileExtentDeg(level); }

// Tiles are built within this share of Cesium's geometric error: the rest covers what the
// construction does not see (heights quantized to 16 bits of the tile's range, a sample moved
// to its quantized position, the chord's sag between points).
constexpr double kBoundMargin = 0.9;

// Tiles of `level` that touch the data's box; every tile of the levels up to `globeLevels`
// (Cesium needs level 0's two roots, and draws the rest of the planet from the deepest level
// it finds there).
TileRange tilesCovering(const LonLatBox& box, int level, int globeLevels) {
  if (level <= std::max(globeLevels, 0)) return {0, 0, (2 << level) - 1, (1 << level) - 1};
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
  QuantizedMeshTileStats stats;
};

// Tiles go into the temporary folder, renamed as a whole at the end.
Status writeFile(const fs::path& path, std::span<const std::byte> bytes) {
  return writeBytesChecked(path, bytes, path);
}

// The tiles of `ranges` under tile (level, x, y) at the next `levels` levels, as the metadata
// extension's JSON: {"available": [[range of level + 1], [range of level + 2], ...]}, ranges in
// TMS order (y from the south), as in layer.json. Written, with an empty list, also when no
// tile lies under it: Cesium takes a tile without it to leave its descendants unknown and
// keeps asking for them.
std::string tileMetadataJson(const std::vector<TileRange>& ranges, int level, int x, int y, int levels) {
  nlohmann::json available = nlohmann::json::array();
  for (int depth = 1; depth <= levels && level + depth < int(ranges.size()); ++depth) {
    const TileRange& all = ranges[std::size_t(level + depth)];
    const TileRange under{std::max(all.x0, x << depth), std::max(all.y0, y << depth),
                          std::min(all.x1, ((x + 1) << depth) - 1), std::min(all.y1, ((y + 1) << depth) - 1)};
    if (under.x0 > under.x1 || under.y0 > under.y1) break;  // nested ranges: none deeper either
    available.push_back(nlohmann::json::array(
        {{{"startX", under.x0}, {"startY", under.y0}, {"endX", under.x1}, {"endY", under.y1}}}));
  }
  return nlohmann::json{{"available", available}}.dump();
}

std::string layerJson(const std::vector<TileRange>& ranges, const TileStore& store, bool waterMask,
                      int metadataLevels) {
  nlohmann::json available = nlohmann::json::array();
  for (const TileRange& r : ranges) {
    available.push_back(nlohmann::json::array(
        {{{"startX", r.x0}, {"startY", r.y0}, {"endX", r.x1}, {"endY", r.y1}}}));
  }
  nlohmann::json extensions = {"octvertexnormals"};
  if (waterMask) extensions.push_back("watermask");
  if (metadataLevels > 0) extensions.push_back("metadata");
  nlohmann::json layer = {
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
      {"extensions", extensions},
      {"available", available}};
  if (metadataLevels > 0) layer["metadataAvailability"] = metadataLevels;
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
  if (options.metadataLevels < 0 || options.metadataLevels > 20) {
    return makeError("metadata every {} levels: it must be 0 (none) to 20", options.metadataLevels);
  }
  std::uint64_t totalTiles = 0;
  if (options.globeLevels > 8) {
    return makeError("--globe-levels {} would write {} tiles of the whole globe; give at most 8",
                     options.globeLevels, 2 * ((std::uint64_t(1) << (2 * options.globeLevels + 2)) - 1) / 3);
  }
  std::vector<TileRange> ranges;
  for (int level = 0; level <= maxLevel; ++level) {
    ranges.push_back(tilesCovering(box, level, options.globeLevels));
    totalTiles += ranges.back().count();
  }
  if (Status fits = checkTileSetFits(folder, totalTiles, maxLevel, naturalMaxLevel); !fits) {
    return fits.error();
  }

  sweepLegacyTemporaries(folder, kind);
  Result<FolderOutput> output = FolderOutput::begin(folder, kind);
  if (!output) return output.error();
  const fs::path temporary = output->temporary();
  std::error_code ec;

  QuantizedMeshExportReport report;
  std::atomic<std::uint64_t> tilesDone{0};
  for (int level = 0; level <= maxLevel; ++level) {
    QuantizedMeshTileOptions tileOptions;
    tileOptions.maxErrorM = cesiumGeometricErrorM(level) * kBoundMargin;
    // The lattice that stands for the ground where there is no data: at least 65 a side, so
    // that the surface's sag between its points stays a few per cent of the bound (4 km
    // against 69 km at level 0; a 17-point lattice would leave 60 km unmeasured).
    tileOptions.latticeSamples = std::max(n, 65);
    tileOptions.geoid = options.geoid;
    tileOptions.dataBounds = box;
    tileOptions.waterMask = options.waterMask;
    const TileRange range = ranges[std::size_t(level)];
    const bool carriesMetadata = options.metadataLevels > 0 && level % options.metadataLevels == 0;
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
      Result<QuantizedMeshTile> tile =
          buildQuantizedMeshTile(level0.value(), {level, x, y}, tileOptions, results[k].stats);
      if (tile && carriesMetadata) {
        tile->metadataJson = tileMetadataJson(ranges, level, x, y, options.metadataLevels);
      }
      Result<std::vector<std::byte>> bytes =
          tile ? encodeQuantizedMesh(tile.value()) : Result<std::vector<std::byte>>(tile.error());
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
    levelReport.geometricErrorM = cesiumGeometricErrorM(level);
    levelReport.tiles = results.size();
    for (const TileResult& r : results) {
      levelReport.bytes += r.bytes;
      levelReport.triangles += r.stats.triangles;
      levelReport.truthSamples += r.stats.truthSamples;
      levelReport.truthStride = std::max(levelReport.truthStride, r.stats.truthStride);
      levelReport.maxErrorM = std::max(levelReport.maxErrorM, r.stats.maxErrorM);
    }
    report.tiles += levelReport.tiles;
    report.bytes += levelReport.bytes;
    report.levels.push_back(levelReport);
  }
  const std::string layer = layerJson(ranges, store, options.waterMask != nullptr, options.metadataLevels);
  if (Status s = writeFile(temporary / "layer.json", std::as_bytes(std::span(layer))); !s) {
    return s.error();
  }
  if (Status s = output->commit(); !s) return s.error();
  return report;
}

}  // namespace tellus
