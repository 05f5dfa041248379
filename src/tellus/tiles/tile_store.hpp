#pragma once
// Reads a .tstore file (store_format.hpp). The file is untrusted: open() validates the header,
// metadata and index (checksums, bounds, every tile of the pyramid present exactly once), and
// every tile read checks the payload's checksum before decoding, so a truncated or corrupted
// store gives an Error naming the tile, never a crash.
//
// Thread-safe after open(): tiles may be read from many threads at once (pread, const codec).
#include <cstdint>
#include <filesystem>
#include <memory>
#include <span>
#include <vector>

#include "tellus/core/result.hpp"
#include "tellus/dem/height_grid.hpp"
#include "tellus/tiles/byte_source.hpp"
#include "tellus/tiles/store_container.hpp"
#include "tellus/tiles/store_metadata.hpp"
#include "tellus/tiles/tile_codec.hpp"
#include "tellus/tiles/tile_record.hpp"

namespace tellus {

class TileStore {
 public:
  // `path`: a file or an http(s):// URL (byte_source.hpp).
  static Result<std::shared_ptr<TileStore>> open(const std::filesystem::path& path);
  // The same from its container, already read (by a caller that looked at its format first).
  static Result<std::shared_ptr<TileStore>> open(const std::filesystem::path& path, StoreContainer container);
  // The byte source (HttpByteSource for URLs: its request counters).
  const ByteSource& source() const { return *source_; }
  ~TileStore();
  TileStore(const TileStore&) = delete;
  TileStore& operator=(const TileStore&) = delete;

  const std::filesystem::path& path() const { return path_; }
  const StoreMetadata& metadata() const { return metadata_; }
  const PyramidLayout& layout() const { return metadata_.layout; }
  const TileCodec& codec() const { return *codec_; }
  std::uint64_t fileBytes() const { return fileBytes_; }
  // All tiles, sorted by (level, y, x).
  std::span<const TileRecord> records() const { return records_; }
  // nullptr when the key is outside the pyramid.
  const TileRecord* find(TileKey key) const;

  // Reads and checksums a tile's payload into `payload` (resized).
  Status readPayload(const TileRecord& record, std::vector<std::byte>& payload) const;
  // Reads, checks and decodes a tile: `samples` holds layout().tileShape().sampleCount() values
  // (quantum steps).
  Status readTile(TileKey key, std::span<std::int32_t> samples) const;
  // The same in metres.
  Status readTileMetres(TileKey key, std::span<float> heights) const;

  // "tile 2/5/7 (level/x/y)" for messages.
  static std::string describe(TileKey key);

 private:
  TileStore() = default;
  Status decodeChecked(const TileRecord& record, std::span<std::int32_t> samples) const;

  std::filesystem::path path_;  // the file or URL
  std::shared_ptr<ByteSource> source_;
  std::uint64_t fileBytes_ = 0;
  StoreMetadata metadata_;
  std::unique_ptr<TileCodec> codec_;
  std::vector<TileRecord> records_;
  std::vector<std::size_t> levelStart_;  // index of each level's first record
};

// Assembles the data area of one level into a HeightGrid (metres, with georeferencing and
// spacing of that level): dataWidthAt(level) x dataHeightAt(level) samples.
Result<HeightGrid> readStoreLevel(const TileStore& store, int level);

// True when the file starts with the tile store magic (cheap test for "is this a store?").
bool looksLikeTileStore(const std::filesystem::path& path);

}  // namespace tellus
