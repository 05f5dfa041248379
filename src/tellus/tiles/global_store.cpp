#include "tellus/tiles/global_store.hpp"

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <tuple>

#include "tellus/tiles/sample_coding.hpp"
#include "tellus/tiles/store_container.hpp"

namespace tellus {
namespace fs = std::filesystem;
namespace sf = store_format;

const char* const kWgs84Wkt =
    "GEOGCS[\"WGS 84\",DATUM[\"WGS_1984\",SPHEROID[\"WGS 84\",6378137,298.257223563,"
    "AUTHORITY[\"EPSG\",\"7030\"]],AUTHORITY[\"EPSG\",\"6326\"]],PRIMEM[\"Greenwich\",0,"
    "AUTHORITY[\"EPSG\",\"8901\"]],UNIT[\"degree\",0.0174532925199433,AUTHORITY[\"EPSG\","
    "\"9122\"]],AXIS[\"Latitude\",NORTH],AXIS[\"Longitude\",EAST],AUTHORITY[\"EPSG\",\"4326\"]]";

namespace {

// A tile's index statistics must mean something (renderers take them as they are).
Status checkStats(const GlobalStoreMetadata& m, const TileStats& stats, bool hasChildren) {
  const double lo = stats.minHeightM, hi = stats.maxHeightM, error = stats.geometricErrorM;
  if (!std::isfinite(lo) || !std::isfinite(hi) || !(lo <= hi)) {
    return makeError("has a nonsensical height range {}..{} m in the index", lo, hi);
  }
  const double slack = 0.5 * m.quantumM + 1e-6 * std::max({1.0, std::abs(double(m.minHeightM)),
                                                           std::abs(double(m.maxHeightM))});
  if (lo < m.minHeightM - slack || hi > m.maxHeightM + slack) {
    return makeError("claims heights {}..{} m outside the store's {}..{} m", lo, hi,
                     m.minHeightM, m.maxHeightM);
  }
  const double relief = double(m.maxHeightM) - double(m.minHeightM);
  if (!std::isfinite(error) || error < 0.0 || error > relief + slack ||
      (!hasChildren && error != 0.0)) {
    return makeError("has a nonsensical geometric error {} m in the index", error);
  }
  return {};
}

}  // namespace

std::string GlobalStore::describe(GeoTileKey key) {
  return fmt::format("tile {}/{}/{} (depth/x/y)", key.depth, key.x, key.y);
}

GlobalStore::~GlobalStore() = default;

bool isGlobalStore(const fs::path& path) {
  Result<StoreContainer> container = readStoreContainer(path.string());
  if (!container) return false;
  return storeFormatName(container->metadataJson) == "tellus-global-store";
}

Result<std::shared_ptr<GlobalStore>> GlobalStore::open(const fs::path& path) {
  Result<StoreContainer> container = readStoreContainer(path.string());
  if (!container) return container.error();
  return open(path, std::move(container.value()));
}

Result<std::shared_ptr<GlobalStore>> GlobalStore::open(const fs::path& path, StoreContainer container) {
  std::shared_ptr<GlobalStore> store(new GlobalStore());
  store->path_ = path;
  const std::string name = path.string();
  store->source_ = container.source;
  store->fileBytes_ = container.fileBytes;
  if (storeFormatName(container.metadataJson) != "tellus-global-store") {
    return makeError("'{}' is a flat tile store, not a global one (build one with tellus build "
                     "--global)",
                     name);
  }
  Result<GlobalStoreMetadata> metadata = globalMetadataFromJson(container.metadataJson);
  if (!metadata) return makeError("'{}': {}", name, metadata.error().message);
  store->metadata_ = std::move(metadata.value());
  const GlobalStoreMetadata& m = store->metadata_;

  CodecOptions codecOptions;
  codecOptions.maxErrorSteps = m.maxErrorSteps;
  Result<std::unique_ptr<TileCodec>> codec =
      makeCodec(CodecId(container.header.codec), codecOptions);
  if (!codec) return makeError("'{}': {}", name, codec.error().message);
  if (codec.value()->name() != m.codec) {
    return makeError("'{}': header says codec '{}', metadata says '{}'", name,
                     codec.value()->name(), m.codec);
  }
  store->codec_ = std::move(codec.value());

  // Keys sorted, unique, inside the tiling and the store's depths, counted as the metadata
  // says; payloads inside the file.
  std::vector<std::uint64_t> perDepth(std::size_t(m.deepestDepth + 1), 0);
  store->records_.reserve(container.index.size());
  for (std::size_t i = 0; i < container.index.size(); ++i) {
    const sf::IndexRecord& r = container.index[i];
    const GeoTileKey key{int(std::min<std::uint32_t>(r.level, 1000)), int(std::min<std::uint32_t>(r.x, 1u << 31)),
                         int(std::min<std::uint32_t>(r.y, 1u << 31))};
    if (r.level > std::uint32_t(m.deepestDepth) || !GlobalTiling::contains(key)) {
      return makeError("'{}': index entry {} ({}/{}/{}) is not a tile of the store's depths",
                       name, i, r.level, r.x, r.y);
    }
    if (i > 0) {
      const sf::IndexRecord& p = container.index[i - 1];
      if (std::tie(p.level, p.y, p.x) >= std::tie(r.level, r.y, r.x)) {
        return makeError("'{}': tile index entry {} is out of order or repeated", name, i);
      }
    }
    if (!payloadInsideFile(r, container.header)) {
      return makeError("'{}': {} points outside the tile data", name, describe(key));
    }
    ++perDepth[std::size_t(key.depth)];
    store->byKey_.emplace(toTileKey(key), store->records_.size());
    store->records_.push_back({toTileKey(key), r.payloadOffset, r.payloadBytes, r.payloadHash,
                               {r.minHeightM, r.maxHeightM, r.geometricErrorM, r.uncoveredSamples}});
  }
  if (perDepth != m.tilesPerDepth) {
    return makeError("'{}': the index does not hold the tiles the metadata counts per depth",
                     name);
  }
  for (const TileRecord& record : store->records_) {
    const GeoTileKey key = toGeoKey(record.key);
    if (key.depth > 0 && !store->find(GlobalTiling::parent(key))) {
      return makeError("'{}': {} is stored but its parent is not", name, describe(key));
    }
    if (Status s = checkStats(m, record.stats, store->hasStoredChildren(key)); !s) {
      return makeError("'{}': {} {}", name, describe(key), s.error().message);
    }
  }
  return store;
}

const TileRecord* GlobalStore::find(GeoTileKey key) const {
  const auto it = byKey_.find(toTileKey(key));
  return it == byKey_.end() ? nullptr : &records_[it->second];
}

GeoTileKey GlobalStore::deepestStored(GeoTileKey key) const {
  while (key.depth > 0 && !find(key)) key = GlobalTiling::parent(key);
  return key;
}

bool GlobalStore::hasStoredChildren(GeoTileKey key) const {
  if (key.depth >= metadata_.deepestDepth) return false;
  for (const GeoTileKey& child : GlobalTiling::children(key)) {
    if (find(child)) return true;
  }
  return false;
}

Status GlobalStore::readTile(GeoTileKey key, std::span<std::int32_t> samples) const {
  const TileRecord* record = find(key);
  if (!record) return makeError("'{}' has no {}", path_.string(), describe(key));
  if (samples.size() != tileShape().sampleCount()) {
    return makeError("readTile: buffer of {} samples for {}", samples.size(), describe(key));
  }
  struct PayloadTag;
  std::vector<std::byte>& payload = coding::threadScratch<std::byte, PayloadTag>(0);
  if (Status s = readCheckedPayload(*source_, *record, describe(key), payload); !s) return s;
  if (Status s = codec_->decode(payload, tileShape(), samples); !s) {
    return makeError("'{}': cannot decode {}: {}", path_.string(), describe(key),
                     s.error().message);
  }
  return {};
}

Status GlobalStore::readTileMetres(GeoTileKey key, std::span<float> heights) const {
  struct SamplesTag;
  std::vector<std::int32_t>& samples =
      coding::threadScratch<std::int32_t, SamplesTag>(tileShape().sampleCount());
  if (heights.size() != samples.size()) {
    return makeError("readTileMetres: buffer of {} samples for {}", heights.size(), describe(key));
  }
  if (Status s = readTile(key, samples); !s) return s;
  for (std::size_t i = 0; i < samples.size(); ++i) {
    heights[i] = float(double(samples[i]) * metadata_.quantumM);
  }
  return {};
}

StoreSampleSource storeSampleSource(const GlobalStore& store, GeoTileKey key, int column,
                                    int row) {
  const int n = store.tileCells();
  const int columns = GlobalTiling::tilesX(key.depth), rows = GlobalTiling::tilesY(key.depth);
  // The tile the sample is read through (key, or a neighbour holding the same point) and its
  // source: the deepest among the tiles that hold the point; key itself on ties.
  GeoTileKey through = key, source = store.deepestStored(key);
  int throughColumn = column, throughRow = row;
  for (int dy = (row == 0 ? -1 : 0); dy <= (row == n ? 1 : 0); ++dy) {
    for (int dx = (column == 0 ? -1 : 0); dx <= (column == n ? 1 : 0); ++dx) {
      const int y = key.y + dy;
      if ((dx == 0 && dy == 0) || y < 0 || y >= rows) continue;
      const GeoTileKey other{key.depth, (key.x + dx + columns) % columns, y};
      const GeoTileKey otherSource = store.deepestStored(other);
      if (otherSource.depth > source.depth) {
        through = other, source = otherSource;
        throughColumn = column - dx * n, throughRow = row - dy * n;
      }
    }
  }
  // The sample's position in the source's cells: 2^shift tiles of key.depth a side per source
  // tile, `through` at its offset among them.
  const int shift = through.depth - source.depth;
  StoreSampleSource result;
  result.source = source;
  result.scale = 1.0 / double(std::int64_t(1) << shift);
  result.u = (double(through.x - (std::int64_t(source.x) << shift)) * n + throughColumn) * result.scale;
  result.v = (double(through.y - (std::int64_t(source.y) << shift)) * n + throughRow) * result.scale;
  return result;
}

Result<HeightGrid> readGlobalRegion(const GlobalStore& store, int depth, const GeoBounds& box,
                                    std::uint64_t maxSamples) {
  if (depth < 0 || depth > GlobalTiling::kMaxDepth) {
    return makeError("depth {} is outside 0..{}", depth, GlobalTiling::kMaxDepth);
  }
  const int n = store.tileCells();
  const double step = GlobalTiling::tileSizeDeg(depth) / n;
  const std::int64_t lastColumn = std::int64_t(GlobalTiling::tilesX(depth)) * n;
  const std::int64_t lastRow = std::int64_t(GlobalTiling::tilesY(depth)) * n;
  const bool allLongitudes = box.eastDeg - box.westDeg >= 360.0 - 1e-9;
  std::int64_t i0 = 0, i1 = lastColumn - 1;
  if (!allLongitudes) {
    i0 = std::clamp<std::int64_t>(std::int64_t(std::floor((box.westDeg + 180.0) / step)), 0, lastColumn);
    i1 = std::clamp<std::int64_t>(std::int64_t(std::ceil((box.eastDeg + 180.0) / step)), 0, lastColumn);
  }
  const std::int64_t j0 =
      std::clamp<std::int64_t>(std::int64_t(std::floor((90.0 - box.northDeg) / step)), 0, lastRow);
  const std::int64_t j1 =
      std::clamp<std::int64_t>(std::int64_t(std::ceil((90.0 - box.southDeg) / step)), 0, lastRow);
  if (!(i1 > i0 && j1 > j0)) {
    return makeError("the region {},{} .. {},{} (degrees) holds no cell at depth {}", box.westDeg,
                     box.southDeg, box.eastDeg, box.northDeg, depth);
  }
  const std::uint64_t samples = std::uint64_t(i1 - i0 + 1) * std::uint64_t(j1 - j0 + 1);
  if (samples > maxSamples || i1 - i0 + 1 > kMaxGridSide || j1 - j0 + 1 > kMaxGridSide) {
    return makeError("the region at depth {} has {} x {} samples, more than {}: use a shallower "
                     "depth or a smaller region",
                     depth, i1 - i0 + 1, j1 - j0 + 1, maxSamples);
  }
  HeightGrid grid(int(i1 - i0 + 1), int(j1 - j0 + 1));
  grid.georef.crsWkt = kWgs84Wkt;
  grid.georef.crsName = "WGS 84";
  grid.georef.isGeographic = true;
  grid.georef.hasGeoTransform = true;
  grid.georef.geoTransform = {-180.0 + double(i0) * step - 0.5 * step, step, 0.0,
                              90.0 - double(j0) * step + 0.5 * step, 0.0, -step};
  const double midLat = 90.0 - 0.5 * double(j0 + j1) * step;
  grid.spacingYM = step * 110'574.0;
  grid.spacingXM = std::max(step * 111'320.0 * std::cos(midLat * M_PI / 180.0), 1e-3);

  // Tile by tile of `depth`; a missing tile is upsampled from its deepest stored ancestor.
  std::map<GeoTileKey, std::vector<float>> decoded;
  const auto tileHeights = [&](GeoTileKey key) -> Result<const std::vector<float>*> {
    auto it = decoded.find(key);
    if (it == decoded.end()) {
      std::vector<float> heights(store.tileShape().sampleCount());
      if (Status s = store.readTileMetres(key, heights); !s) return s.error();
      it = decoded.emplace(key, std::move(heights)).first;
    }
    return &it->second;
  };
  const int t0x = int(i0 / n), t1x = int(std::min(i1, lastColumn - 1) / n);
  const int t0y = int(j0 / n), t1y = int(std::min(j1, lastRow - 1) / n);
  // Shallow sources first, the deepest last: on an edge between tiles the deepest source wins
  // (storeSampleSource's rule; sources of equal depth agree there).
  std::vector<std::pair<GeoTileKey, GeoTileKey>> tiles;  // (tile, where its heights come from)
  for (int ty = t0y; ty <= t1y; ++ty) {
    for (int tx = t0x; tx <= t1x; ++tx) {
      const GeoTileKey key{depth, tx, ty};
      tiles.emplace_back(key, store.deepestStored(key));
    }
  }
  std::stable_sort(tiles.begin(), tiles.end(), [](const auto& a, const auto& b) {
    return a.second.depth < b.second.depth;
  });
  for (const auto& [key, source] : tiles) {
    {
      const int tx = key.x, ty = key.y;
      Result<const std::vector<float>*> heights = tileHeights(source);
      if (!heights) return heights.error();
      const std::vector<float>& h = *heights.value();
      const int shift = depth - source.depth;  // ancestor samples are 2^shift of ours apart
      const double scale = 1.0 / double(std::int64_t(1) << shift);
      const std::int64_t originX = std::int64_t(source.x) * n, originY = std::int64_t(source.y) * n;
      for (std::int64_t j = std::max<std::int64_t>(j0, std::int64_t(ty) * n);
           j <= std::min<std::int64_t>(j1, std::int64_t(ty + 1) * n); ++j) {
        const double v = double(j) * scale - double(originY);
        for (std::int64_t i = std::max<std::int64_t>(i0, std::int64_t(tx) * n);
             i <= std::min<std::int64_t>(i1, std::int64_t(tx + 1) * n); ++i) {
          const double u = double(i) * scale - double(originX);
          grid.at(int(i - i0), int(j - j0)) = float(tileSurfaceAt(h, n, u, v));
        }
      }
    }
  }
  return grid;
}

Result<HeightGrid> readGlobalTileSurface(const GlobalStore& store, GeoTileKey key) {
  if (key.depth < 0 || key.depth > GlobalTiling::kMaxDepth || !GlobalTiling::contains(key)) {
    return makeError("{} is outside the global tiling", GlobalStore::describe(key));
  }
  const int n = store.tileCells();
  const double step = GlobalTiling::tileSizeDeg(key.depth) / n;
  const GeoBounds bounds = GlobalTiling::bounds(key);
  HeightGrid grid(n + 1, n + 1);
  grid.georef.crsWkt = kWgs84Wkt;
  grid.georef.crsName = "WGS 84";
  grid.georef.isGeographic = true;
  grid.georef.hasGeoTransform = true;
  grid.georef.geoTransform = {bounds.westDeg - 0.5 * step, step, 0.0,
                              bounds.northDeg + 0.5 * step, 0.0, -step};
  const double midLat = 0.5 * (bounds.northDeg + bounds.southDeg);
  grid.spacingYM = step * 110'574.0;
  grid.spacingXM = std::max(step * 111'320.0 * std::cos(midLat * M_PI / 180.0), 1e-3);

  std::map<GeoTileKey, std::vector<float>> decoded;  // each source read once
  // Inside the tile every sample comes from key's own source (storeSampleSource's rule with
  // no neighbour to consult), computed once.
  const StoreSampleSource inside = storeSampleSource(store, key, 1, 1);
  const int shift = key.depth - inside.source.depth;
  const double offsetX = double(key.x - (std::int64_t(inside.source.x) << shift)) * n;
  const double offsetY = double(key.y - (std::int64_t(inside.source.y) << shift)) * n;
  for (int row = 0; row <= n; ++row) {
    for (int column = 0; column <= n; ++column) {
      const bool edge = row == 0 || column == 0 || row == n || column == n;
      StoreSampleSource at = inside;
      if (edge) {
        at = storeSampleSource(store, key, column, row);
      } else {
        at.u = (offsetX + column) * inside.scale;  // as storeSampleSource computes it
        at.v = (offsetY + row) * inside.scale;
      }
      auto it = decoded.find(at.source);
      if (it == decoded.end()) {
        std::vector<float> heights(store.tileShape().sampleCount());
        if (Status s = store.readTileMetres(at.source, heights); !s) return s.error();
        it = decoded.emplace(at.source, std::move(heights)).first;
      }
      grid.at(column, row) = float(tileSurfaceAt(it->second, n, at.u, at.v));
    }
  }
  return grid;
}

}  // namespace tellus
