#pragma once
// Writes a .tstore file (store_format.hpp) so that it appears complete or not at all: tiles go
// into a temporary file beside the destination (".NAME.tellus-partial-PID-N"), finish() writes metadata,
// index and header, flushes to disk and renames it over the destination. If the process dies
// at any point before the rename (even SIGKILL), the destination still holds the previous
// store, or nothing; a later writer for the same destination removes temporaries left by
// processes that no longer exist. Not thread-safe: one thread appends.
#include <cstdint>
#include <filesystem>
#include <memory>
#include <span>
#include <vector>

#include "tellus/core/result.hpp"
#include "tellus/tiles/store_format.hpp"
#include "tellus/tiles/store_metadata.hpp"
#include "tellus/tiles/tile_record.hpp"

namespace tellus {

class TileStoreWriter {
 public:
  static Result<std::unique_ptr<TileStoreWriter>> create(const std::filesystem::path& path,
                                                         CodecId codec);
  ~TileStoreWriter();  // removes the temporary file unless finish() succeeded
  TileStoreWriter(const TileStoreWriter&) = delete;
  TileStoreWriter& operator=(const TileStoreWriter&) = delete;

  Status append(TileKey key, std::span<const std::byte> payload, const TileStats& stats);
  // Checks that every tile of metadata.layout was appended exactly once, then completes the
  // file and renames it into place.
  Status finish(const StoreMetadata& metadata);
  // The same for a store whose metadata is not a flat pyramid's (the global store): the caller
  // has checked its tiles; records are written sorted by (level, y, x).
  Status finishWithMetadata(const std::string& metadataJson);
  // Tiles whose payloads others wrote into temporaryPath() (the ranks of a sharded build, with
  // pwrite at places agreed beforehand): takes their records and moves the end of the payloads
  // to `payloadEnd`, where finish writes the metadata and index. Every record must lie between
  // the header and `payloadEnd`, after what this writer appended itself.
  Status placeWrittenTiles(std::span<const TileRecord> records, std::uint64_t payloadEnd);
  // The tiles appended so far, in append order until finish sorts them.
  const std::vector<TileRecord>& records() const { return records_; }

  std::uint64_t payloadBytes() const { return offset_ - store_format::kHeaderBytes; }
  const std::filesystem::path& temporaryPath() const { return temporary_; }

 private:
  TileStoreWriter(std::filesystem::path path, std::filesystem::path temporary, int fd,
                  CodecId codec);
  Status writeAll(const void* data, std::size_t bytes);
  void sortRecords();

  std::filesystem::path path_;
  std::filesystem::path temporary_;
  int fd_ = -1;
  CodecId codec_;
  std::uint64_t offset_ = store_format::kHeaderBytes;
  std::vector<TileRecord> records_;
  bool finished_ = false;
};

}  // namespace tellus
