#include "tellus/tiles/tile_store.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>
#include <cerrno>
#include <cmath>
#include <cstring>

#include "tellus/core/input_file.hpp"
#include "tellus/tiles/sample_coding.hpp"
#include "tellus/tiles/store_container.hpp"
#include "tellus/tiles/store_format.hpp"

namespace tellus {
namespace fs = std::filesystem;
namespace sf = store_format;

namespace {

// readStoreLevel() assembles a level in memory; beyond this (4 GiB of floats) it refuses.
constexpr std::size_t kMaxGridSamples = std::size_t(1) << 30;

// A tile's index statistics must mean something: the reader's users (the rings renderer's
// error metric, culling bounds) take them as they are.
Status checkTileStats(const StoreMetadata& m, TileKey key, const TileStats& stats) {
  const double lo = stats.minHeightM, hi = stats.maxHeightM, error = stats.geometricErrorM;
  if (!std::isfinite(lo) || !std::isfinite(hi) || !(lo <= hi)) {
    return makeError("has a nonsensical height range {}..{} m in the index", lo, hi);
  }
  // Float rounding of sample * quantum, on heights up to 1e6 m.
  const double slack = 0.5 * m.quantumM + 1e-6 * std::max({1.0, std::abs(double(m.minHeightM)),
                                                           std::abs(double(m.maxHeightM))});
  // The store's range is that of level 0; a lossy codec's coarser tiles may reach beyond it by
  // its error.
  const double beyond = slack + (key.level > 0 ? m.maxErrorM : 0.0);
  if (lo < m.minHeightM - beyond || hi > m.maxHeightM + beyond) {
    return makeError("claims heights {}..{} m outside the store's {}..{} m", lo, hi,
                     m.minHeightM, m.maxHeightM);
  }
  const double relief = double(m.maxHeightM) - double(m.minHeightM);
  // Input heights may lie up to the codec's error outside the stored range.
  if (!std::isfinite(error) || error < 0.0 || error > relief + 2.0 * m.maxErrorM + slack ||
      (key.level == 0 && error != 0.0)) {
    return makeError("has a nonsensical geometric error {} m in the index (level {}, relief {} m)",
                     error, key.level, relief);
  }
  return {};
}

}  // namespace

std::string TileStore::describe(TileKey key) {
  return fmt::format("tile {}/{}/{} (level/x/y)", key.level, key.x, key.y);
}

bool looksLikeTileStore(const fs::path& path) {
  // A file is never waited on (a FIFO is refused); a URL costs two small range requests.
  Result<std::shared_ptr<ByteSource>> source = openByteSource(path);
  if (!source) return false;
  std::array<char, 8> magic{};
  const bool read = source.value()->size() >= magic.size() &&
                    source.value()->readAt(magic.data(), magic.size(), 0).ok();
  return read && magic == sf::kMagic;
}

TileStore::~TileStore() = default;

Result<std::shared_ptr<TileStore>> TileStore::open(const fs::path& path) {
  Result<StoreContainer> container = readStoreContainer(path.string());
  if (!container) return container.error();
  return open(path, std::move(container.value()));
}

Result<std::shared_ptr<TileStore>> TileStore::open(const fs::path& path, StoreContainer container) {
  std::shared_ptr<TileStore> store(new TileStore());
  store->path_ = path;
  const std::string name = path.string();
  store->source_ = container.source;
  store->fileBytes_ = container.fileBytes;
  const sf::Header& header = container.header;
  const std::vector<sf::IndexRecord>& index = container.index;
  if (storeFormatName(container.metadataJson) == "tellus-global-store") {
    return makeError(
        "'{}' is a global store (latitude/longitude tiles): it is drawn by the globe "
        "renderers (--algo globe-reference), not on the flat world",
        name);
  }
  Result<StoreMetadata> metadata = metadataFromJson(container.metadataJson);
  if (!metadata) return makeError("'{}': {}", name, metadata.error().message);
  store->metadata_ = std::move(metadata.value());
  const PyramidLayout& layout = store->metadata_.layout;

  CodecOptions codecOptions;
  codecOptions.maxErrorSteps = store->metadata_.maxErrorSteps;
  Result<std::unique_ptr<TileCodec>> codec = makeCodec(CodecId(header.codec), codecOptions);
  if (!codec) return makeError("'{}': {}", name, codec.error().message);
  if (codec.value()->name() != store->metadata_.codec) {
    return makeError("'{}': header says codec '{}', metadata says '{}'", name,
                     codec.value()->name(), store->metadata_.codec);
  }
  store->codec_ = std::move(codec.value());

  if (index.size() != layout.tileCount()) {
    return makeError("'{}' indexes {} tiles, its pyramid has {}", name, index.size(),
                     layout.tileCount());
  }
  // Records must be exactly the pyramid's tiles in (level, y, x) order, payloads inside the
  // payload section.
  store->records_.reserve(index.size());
  std::size_t i = 0;
  for (int level = 0; level < layout.levelCount(); ++level) {
    store->levelStart_.push_back(i);
    for (int y = 0; y < layout.tilesY(level); ++y) {
      for (int x = 0; x < layout.tilesX(level); ++x, ++i) {
        const sf::IndexRecord& r = index[i];
        const TileKey key{level, x, y};
        if (r.level != std::uint32_t(level) || r.x != std::uint32_t(x) || r.y != std::uint32_t(y)) {
          return makeError("'{}': tile index entry {} is not {}", name, i, describe(key));
        }
        if (!payloadInsideFile(r, header)) {
          return makeError("'{}': {} points outside the tile data", name, describe(key));
        }
        const TileStats stats{r.minHeightM, r.maxHeightM, r.geometricErrorM};
        if (Status meaningful = checkTileStats(store->metadata_, key, stats); !meaningful) {
          return makeError("'{}': {} {}", name, describe(key), meaningful.error().message);
        }
        store->records_.push_back({key, r.payloadOffset, r.payloadBytes, r.payloadHash, stats});
      }
    }
  }
  return store;
}

const TileRecord* TileStore::find(TileKey key) const {
  if (!layout().contains(key)) return nullptr;
  const std::size_t i = levelStart_[std::size_t(key.level)] +
                        std::size_t(key.y) * std::size_t(layout().tilesX(key.level)) +
                        std::size_t(key.x);
  return &records_[i];
}

Status TileStore::readPayload(const TileRecord& record, std::vector<std::byte>& payload) const {
  return readCheckedPayload(*source_, record, describe(record.key), payload);
}

Status TileStore::decodeChecked(const TileRecord& record, std::span<std::int32_t> samples) const {
  struct PayloadTag;  // codecs use the untagged byte scratch
  std::vector<std::byte>& payload = coding::threadScratch<std::byte, PayloadTag>(0);
  if (Status s = readPayload(record, payload); !s) return s;
  Status decoded = codec_->decode(payload, layout().tileShape(), samples);
  if (!decoded) {
    return makeError("'{}': cannot decode {}: {}", path_.string(), describe(record.key),
                     decoded.error().message);
  }
  return {};
}

Status TileStore::readTile(TileKey key, std::span<std::int32_t> samples) const {
  const TileRecord* record = find(key);
  if (!record) return makeError("'{}' has no {}", path_.string(), describe(key));
  if (samples.size() != layout().tileShape().sampleCount()) {
    return makeError("readTile: buffer of {} samples for {}", samples.size(), describe(key));
  }
  return decodeChecked(*record, samples);
}

Status TileStore::readTileMetres(TileKey key, std::span<float> heights) const {
  struct SamplesTag;
  std::vector<std::int32_t>& samples =
      coding::threadScratch<std::int32_t, SamplesTag>(layout().tileShape().sampleCount());
  if (heights.size() != samples.size()) {
    return makeError("readTileMetres: buffer of {} samples for {}", heights.size(), describe(key));
  }
  if (Status s = readTile(key, samples); !s) return s;
  const double q = metadata_.quantumM;
  for (std::size_t i = 0; i < samples.size(); ++i) heights[i] = float(double(samples[i]) * q);
  return {};
}

Result<HeightGrid> readStoreLevel(const TileStore& store, int level) {
  const PyramidLayout& layout = store.layout();
  if (level < 0 || level >= layout.levelCount()) {
    return makeError("level {} does not exist: '{}' has levels 0 to {}", level,
                     store.path().string(), layout.levelCount() - 1);
  }
  const StoreMetadata& m = store.metadata();
  const int stride = PyramidLayout::stride(level);
  const std::size_t samples =
      std::size_t(layout.dataWidthAt(level)) * std::size_t(layout.dataHeightAt(level));
  if (samples > kMaxGridSamples) {
    return makeError(
        "level {} of '{}' has {} x {} samples, more than {} fit in memory at once; "
        "use a coarser --level",
        level, store.path().string(), layout.dataWidthAt(level), layout.dataHeightAt(level),
        kMaxGridSamples);
  }
  HeightGrid grid(layout.dataWidthAt(level), layout.dataHeightAt(level));
  grid.spacingXM = m.spacingXM * stride;
  grid.spacingYM = m.spacingYM * stride;
  grid.georef = m.georef;
  grid.filledVoidCount = m.filledVoidCount;
  if (grid.georef.hasGeoTransform && stride > 1) {
    // Sample c of this level is sample c * stride of level 0; keep sample centres in place.
    std::array<double, 6>& gt = grid.georef.geoTransform;
    const double shift = 0.5 - 0.5 * stride;  // in level-0 pixels
    gt[0] += shift * (gt[1] + gt[2]);
    gt[3] += shift * (gt[4] + gt[5]);
    for (int i : {1, 2, 4, 5}) gt[std::size_t(i)] *= stride;
  }
  const int n = layout.tileSize();
  std::vector<float> tile(layout.tileShape().sampleCount());
  for (int ty = 0; ty < layout.tilesY(level); ++ty) {
    for (int tx = 0; tx < layout.tilesX(level); ++tx) {
      if (Status s = store.readTileMetres({level, tx, ty}, tile); !s) return s.error();
      for (int j = 0; j <= n; ++j) {
        const int row = ty * n + j;
        if (row >= grid.height) break;
        for (int i = 0; i <= n; ++i) {
          const int col = tx * n + i;
          if (col >= grid.width) break;
          grid.at(col, row) = tile[std::size_t(j) * std::size_t(n + 1) + std::size_t(i)];
        }
      }
    }
  }
  return grid;
}

}  // namespace tellus
