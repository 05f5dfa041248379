#pragma once
// The checksums of a .tstore file (store_format.hpp), in one place for the writer and the
// reader. Every section has an xxh64: the header its own, metadata and index theirs, and each
// tile payload one seeded with the tile's key, so a payload moved or swapped to another tile's
// place fails its checksum even though its bytes are intact.
//
// Fuzzing builds (TELLUS_FUZZ_SKIP_CHECKSUMS) compute the checksums but do not compare them, so
// that mutated inputs reach metadata parsing, index validation and decoding.
#include <cstdint>
#include <span>

#include "tellus/tiles/pyramid_layout.hpp"

namespace tellus::store_format {

#ifdef TELLUS_FUZZ_SKIP_CHECKSUMS
inline constexpr bool kCompareChecksums = false;
#else
inline constexpr bool kCompareChecksums = true;
#endif

// xxh64 (seed 0) of a section.
std::uint64_t sectionChecksum(std::span<const std::byte> bytes);
// xxh64 of a tile's payload, seeded with its key (format version 2).
std::uint64_t payloadChecksum(std::span<const std::byte> payload, TileKey key);

// True when `actual` matches `expected` (always true in fuzzing builds).
inline bool checksumMatches(std::uint64_t actual, std::uint64_t expected) {
  return !kCompareChecksums || actual == expected;
}

}  // namespace tellus::store_format
