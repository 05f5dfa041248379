#pragma once
// Editing Tellus's files and writing them back with every checksum recomputed, so that tests can
// hand the readers files that are well-formed but mean nonsense (the corruption a checksum
// cannot catch): .tstore sections, a .tstack's header, a .bdam's parts.
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

// Index records `a` and `b` trade their payloads (offset, size, checksum) and heights: two tiles
// in each other's place, each as consistent as a forger can make it.
void swapTilePayloads(StoreSections& sections, std::size_t a, std::size_t b);

// A .tstack's bytes whose header or level table was edited: the header checksum recomputed
// (xxh64 of the header and table, its own 8 bytes zeroed).
void resealStackHeader(std::string& bytes);

// A .bdam file as header (64 bytes), table (56 bytes a patch) and data.
struct BdamParts {
  std::vector<std::byte> header, table, data;
};
BdamParts readBdamParts(const std::filesystem::path& file);
// Writes `parts` with each patch's, the table's and the header's checksums recomputed.
void writeBdamParts(BdamParts parts, const std::filesystem::path& file);

}  // namespace tellus::test
