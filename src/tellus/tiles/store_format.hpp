#pragma once
// The on-disk layout of a .tstore file (version 2). All integers little-endian.
//
//   [Header, 96 bytes]
//   [tile payloads, back to back, in the order they were built]
//   [metadata: UTF-8 JSON (store_metadata.hpp)]
//   [index: tileCount IndexRecords of 48 bytes, sorted by (level, y, x)]
//
// The header is written last, so a file without a valid header is never mistaken for a store;
// the builder writes a temporary file and renames it into place (see tile_store_writer.hpp).
// Every section has an xxh64 checksum (store_checksums.hpp): the header its own, metadata and
// index theirs, and each tile payload one in its index record, seeded with the tile's key.
// Version 1 (until 2026-12) seeded payload checksums with 0, so swapped tiles went unnoticed;
// the reader refuses it and asks for a rebuild.
#include <array>
#include <bit>
#include <cstdint>
#include <cstring>

namespace tellus::store_format {

static_assert(std::endian::native == std::endian::little, "the store format is little-endian");

inline constexpr std::array<char, 8> kMagic{'T', 'E', 'L', 'L', 'U', 'S', 'T', 'S'};
inline constexpr std::uint32_t kVersion = 2;
inline constexpr std::size_t kHeaderBytes = 96;
inline constexpr std::size_t kIndexRecordBytes = 48;

struct Header {
  std::array<char, 8> magic = kMagic;
  std::uint32_t version = kVersion;
  std::uint32_t headerBytes = kHeaderBytes;
  std::uint32_t codec = 0;  // CodecId
  std::uint32_t tileCount = 0;
  std::uint64_t fileBytes = 0;  // the whole file; a shorter file was truncated
  std::uint64_t metadataOffset = 0;
  std::uint64_t metadataBytes = 0;
  std::uint64_t indexOffset = 0;
  std::uint64_t indexBytes = 0;
  std::uint64_t metadataHash = 0;  // xxh64, seed 0
  std::uint64_t indexHash = 0;
  std::uint64_t reserved = 0;
  std::uint64_t headerHash = 0;  // xxh64 of the 88 bytes before it
};
static_assert(sizeof(Header) == kHeaderBytes);

struct IndexRecord {
  std::uint32_t level = 0;
  std::uint32_t x = 0;
  std::uint32_t y = 0;
  std::uint32_t payloadBytes = 0;
  std::uint64_t payloadOffset = 0;
  std::uint64_t payloadHash = 0;  // payloadChecksum() of the payload and its key
  float minHeightM = 0.0f;        // of the tile's samples
  float maxHeightM = 0.0f;
  float geometricErrorM = 0.0f;  // see TileRecord
  std::uint32_t uncoveredSamples = 0;  // see TileStats; 0 in flat stores
};
static_assert(sizeof(IndexRecord) == kIndexRecordBytes);

}  // namespace tellus::store_format
