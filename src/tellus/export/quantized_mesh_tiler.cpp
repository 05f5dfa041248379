#include "tellus/export/quantized_mesh_tiler.hpp"

#include <unistd.h>

#include <algorithm>
#include <atomic>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "tellus/core/atomic_output.hpp"
#include "tellus/core/folder_output.hpp"
#include "tellus/export/geographic_pyramid.hpp"
#include "tellus/export/lonlat_sampler.hpp"
#include "tellus/export/quantized_mesh.hpp"
#include "tellus/export/quantized_mesh_tile_builder.hpp"

namespace tellus {
namespace fs = std::filesystem;

namespace {

// Tiles go into the temporary folder, renamed as a whole at the end.
Status writeFile(const fs::path& path, std::span<const std::byte> bytes) {
  return writeBytesChecked(path, bytes, path);
}

// The tiles of `ranges` under tile (level, x, y) at the next `levels` levels, as the metadata
// extension's JSON: {"available": [[range of level + 1], [range of level + 2], ...]}, ranges in
// TMS order (y from the south), as in layer.json. Written, with an empty list, also when no
// tile lies under it: Cesium takes a tile without it to leave its descendants unknown and
// keeps asking for them.
std::string tileMetadataJson(const std::vector<GeographicTileRange>& ranges, int level, int x, int y, int levels) {
  nlohmann::json available = nlohmann::json::array();
  for (int depth = 1; depth <= levels && level + depth < int(ranges.size()); ++depth) {
    const GeographicTileRange& all = ranges[std::size_t(level + depth)];
    const GeographicTileRange under{std::max(all.x0, x << depth), std::max(all.y0, y << depth),
                          std::min(all.x1, ((x + 1) << depth) - 1), std::min(all.y1, ((y + 1) << depth) - 1)};
    if (under.x0 > under.x1 || under.y0 > under.y1) break;  // nested ranges: none deeper either
    available.push_back(nlohmann::json::array(
        {{{"startX", under.x0}, {"startY", under.y0}, {"endX", under.x1}, {"endY", under.y1}}}));
  }
  return nlohmann::json{{"available", available}}.dump();
}

std::string layerJson(const std::vector<GeographicTileRange>& ranges, const TileStore& store, bool waterMask,
                      int metadataLevels) {
  nlohmann::json available = nlohmann::json::array();
  for (const GeographicTileRange& r : ranges) {
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
    std::vector<std::string> parts;
    for (const fs::path& part : relative) parts.push_back(part.string());
    if (parts.size() == 1 && parts[0] == "layer.json") return true;
    if (parts.empty() || parts.size() > 3) return false;
    for (std::size_t k = 0; k + 1 < parts.size(); ++k) {
      if (!isTileNumberName(parts[k])) return false;
    }
    const std::string& last = parts.back();
    if (parts.size() < 3) return isTileNumberName(last);
    return last.size() > 8 && last.ends_with(".terrain") && isTileNumberName(last.substr(0, last.size() - 8));
  };
  return kind;
}

namespace {

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
  if (options.metadataLevels < 0 || options.metadataLevels > 20) {
    return makeError("metadata every {} levels: it must be 0 (none) to 20", options.metadataLevels);
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
  Result<GeographicPyramid> planned = planGeographicPyramid(
      level0.value(), store.path().string(), {options.maxLevel, options.tileSamples, options.globeLevels});
  if (!planned) return planned.error();
  const GeographicPyramid& pyramid = planned.value();
  const std::vector<GeographicTileRange>& ranges = pyramid.ranges;
  if (Status fits = checkFilesFit(folder, pyramid.tiles,
                                  fmt::format("a quantized-mesh tile set of levels 0..{}", pyramid.maxLevel),
                                  fmt::format("give a smaller --max-level (the store's samples need no "
                                              "more than level {})", pyramid.naturalMaxLevel));
      !fits) {
    return fits.error();
  }

  sweepLegacyTemporaries(folder, kind);
  Result<FolderOutput> output = FolderOutput::begin(folder, kind);
  if (!output) return output.error();
  const fs::path temporary = output->temporary();
  std::error_code ec;

  QuantizedMeshExportReport report;
  std::atomic<std::uint64_t> tilesDone{0};
  for (int level = 0; level <= pyramid.maxLevel; ++level) {
    QuantizedMeshTileOptions tileOptions;
    // The lattice that stands for the ground where there is no data: at least 65 a side, so
    // that the surface's sag between its points stays a few per cent of the bound (4 km
    // against 69 km at level 0; a 17-point lattice would leave 60 km unmeasured).
    tileOptions.latticeSamples = std::max(options.tileSamples, 65);
    tileOptions.geoid = options.geoid;
    tileOptions.background = options.background;
    tileOptions.dataBounds = pyramid.dataBox;
    tileOptions.waterMask = options.waterMask;
    const GeographicTileRange& range = ranges[std::size_t(level)];
    const bool carriesMetadata = options.metadataLevels > 0 && level % options.metadataLevels == 0;
    for (int x = range.x0; x <= range.x1; ++x) {
      fs::create_directories(temporary / std::to_string(level) / std::to_string(x), ec);
      if (ec) return makeError("cannot create a folder in '{}': {}", temporary.string(), ec.message());
    }
    const int columns = range.x1 - range.x0 + 1;
    std::vector<PyramidTileResult> results(range.count());
    const Status built = forEachPyramidTile(
        pyramid, level,
        [&](int x, int y) -> Status {
          PyramidTileResult& result = results[std::size_t(y - range.y0) * std::size_t(columns) + std::size_t(x - range.x0)];
          QuantizedMeshTileOptions meshOptions = tileOptions;
          meshOptions.maxErrorM = pyramid.tileBoundM(level, x, y);
          meshOptions.edgeErrorM = pyramid.edgeBoundsM(level, x, y);
          Result<QuantizedMeshTile> tile =
              buildQuantizedMeshTile(level0.value(), {level, x, y}, meshOptions, result.stats);
          if (!tile) return tile.error();
          if (carriesMetadata) tile->metadataJson = tileMetadataJson(ranges, level, x, y, options.metadataLevels);
          Result<std::vector<std::byte>> bytes = encodeQuantizedMesh(tile.value());
          if (!bytes) return bytes.error();
          result.bytes = bytes->size();
          return writeFile(temporary / std::to_string(level) / std::to_string(x) / fmt::format("{}.terrain", y),
                           bytes.value());
        },
        [&] {
          const std::uint64_t done = ++tilesDone;
          if (options.progress) options.progress(done, pyramid.tiles);
        });
    if (!built) return built.error();
    const PyramidLevelReport levelReport = summarizeLevel(level, results);
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
