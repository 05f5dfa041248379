#pragma once
// Editing a .tstore file's sections and writing it back with every checksum recomputed, so
// that tests can hand the reader stores that are well-formed but mean nonsense (the corruption
// a checksum cannot catch).
#include <filesystem>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "tellus/core/result.hpp"
#include "tellus/tiles/store_format.hpp"

namespace tellus::test {

struct StoreSections {
  store_format::Header header;
  std::vector<std::byte> payloads;  // everything between the header and the metadata
  nlohmann::json metadata;
  std::vector<store_format::IndexRecord> index;
};

Result<StoreSections> readStoreSections(const std::filesystem::path& store);
// Lays the sections out again (offsets, sizes) and recomputes the header's, metadata's and
// index's checksums, and, when `rehashPayloads`, each payload's for the key its record names
// (false: records keep the payload checksums they carry, as when index entries are swapped).
Status writeStoreSections(const StoreSections& sections, const std::filesystem::path& store,
                          bool rehashPayloads = true);

}  // namespace tellus::test
