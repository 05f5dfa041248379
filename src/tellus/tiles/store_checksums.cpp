#include "tellus/tiles/store_checksums.hpp"

#include <xxhash.h>

#include <array>

namespace tellus::store_format {

std::uint64_t sectionChecksum(std::span<const std::byte> bytes) {
  return XXH64(bytes.data(), bytes.size(), 0);
}

std::uint64_t payloadChecksum(std::span<const std::byte> payload, TileKey key) {
  // The seed is a hash of the key, so every tile position gets its own checksum function.
  const std::array<std::uint32_t, 3> keyWords = {std::uint32_t(key.level), std::uint32_t(key.x),
                                                 std::uint32_t(key.y)};
  const std::uint64_t seed = XXH64(keyWords.data(), sizeof(keyWords), 0x7e11u);
  return XXH64(payload.data(), payload.size(), seed);
}

}  // namespace tellus::store_format
