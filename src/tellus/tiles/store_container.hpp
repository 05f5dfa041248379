#pragma once
// Reading the container every .tstore file shares (store_format.hpp), whatever its tiling: the
// header, the metadata JSON and the index, each checked against its checksum and the file's
// size, and tile payloads checked against theirs. The flat store (tile_store.hpp) and the global
// store (global_store.hpp) parse the metadata and validate the index against their own tiling.
#include <cstdint>
#include <filesystem>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "tellus/core/result.hpp"
#include "tellus/tiles/byte_source.hpp"
#include "tellus/tiles/store_format.hpp"
#include "tellus/tiles/tile_record.hpp"

namespace tellus {

// Reads exactly `bytes` at `offset` (retrying short reads).
Status preadExact(int fd, void* data, std::size_t bytes, std::uint64_t offset);

struct StoreContainer {
  std::shared_ptr<ByteSource> source;  // the file or URL, open
  std::uint64_t fileBytes = 0;
  store_format::Header header;
  std::string metadataJson;
  std::vector<store_format::IndexRecord> index;
};

// Opens and checks the container: magic, version, header checksum, file size, sections inside
// the file, metadata and index checksums. `location`: a file or an http(s):// URL
// (byte_source.hpp).
Result<StoreContainer> readStoreContainer(const std::string& location);

// The metadata's "format" field ("tellus-tile-store", "tellus-global-store"), empty when the
// JSON has none.
std::string storeFormatName(std::string_view metadataJson);

// An index record's payload must lie inside the payload section (before the metadata).
bool payloadInsideFile(const store_format::IndexRecord& record,
                       const store_format::Header& header);

// Reads and checksums one tile payload into `payload` (resized); `describe` names the tile in
// errors ("tile 2/5/7 (level/x/y)").
Status readCheckedPayload(const ByteSource& source, const TileRecord& record,
                          const std::string& describe, std::vector<std::byte>& payload);

}  // namespace tellus
