#include "support/store_surgery.hpp"

#include <xxhash.h>

#include <algorithm>
#include <cstring>
#include <fstream>
#include <iterator>
#include <utility>

#include "tellus/tiles/store_checksums.hpp"

namespace tellus::test {
namespace sf = store_format;

Result<StoreSections> readStoreSections(const std::filesystem::path& store) {
  std::ifstream in(store, std::ios::binary);
  const std::vector<char> bytes((std::istreambuf_iterator<char>(in)),
                                std::istreambuf_iterator<char>());
  if (bytes.size() < sf::kHeaderBytes) return makeError("'{}' is too short", store.string());
  StoreSections s;
  std::memcpy(&s.header, bytes.data(), sizeof(s.header));
  const sf::Header& h = s.header;
  if (h.indexOffset + h.indexBytes > bytes.size()) return makeError("bad sections");
  const auto* base = reinterpret_cast<const std::byte*>(bytes.data());
  s.payloads.assign(base + sf::kHeaderBytes, base + h.metadataOffset);
  s.metadata = nlohmann::json::parse(bytes.begin() + std::ptrdiff_t(h.metadataOffset),
                                     bytes.begin() + std::ptrdiff_t(h.indexOffset));
  s.index.resize(h.tileCount);
  std::memcpy(s.index.data(), bytes.data() + h.indexOffset, h.indexBytes);
  return s;
}

Status writeStoreSections(const StoreSections& s, const std::filesystem::path& store,
                          bool rehashPayloads) {
  sf::Header h = s.header;
  const std::string metadata = s.metadata.dump(1);
  std::vector<sf::IndexRecord> index = s.index;
  for (sf::IndexRecord& r : index) {
    if (rehashPayloads && r.payloadOffset >= sf::kHeaderBytes &&
        r.payloadOffset + r.payloadBytes <= sf::kHeaderBytes + s.payloads.size()) {
      const std::span<const std::byte> payload(
          s.payloads.data() + (r.payloadOffset - sf::kHeaderBytes), r.payloadBytes);
      r.payloadHash = sf::payloadChecksum(
          payload, TileKey{int(r.level), int(r.x), int(r.y)});
    }
  }
  h.tileCount = std::uint32_t(index.size());
  h.metadataOffset = sf::kHeaderBytes + s.payloads.size();
  h.metadataBytes = metadata.size();
  h.indexOffset = h.metadataOffset + h.metadataBytes;
  h.indexBytes = index.size() * sf::kIndexRecordBytes;
  h.fileBytes = h.indexOffset + h.indexBytes;
  h.metadataHash = sf::sectionChecksum(std::as_bytes(std::span(metadata.data(), metadata.size())));
  h.indexHash = sf::sectionChecksum(std::as_bytes(std::span(index)));
  h.headerHash = sf::sectionChecksum(
      std::as_bytes(std::span(&h, 1)).first(offsetof(sf::Header, headerHash)));
  std::ofstream out(store, std::ios::binary | std::ios::trunc);
  out.write(reinterpret_cast<const char*>(&h), sizeof(h));
  out.write(reinterpret_cast<const char*>(s.payloads.data()), std::streamsize(s.payloads.size()));
  out.write(metadata.data(), std::streamsize(metadata.size()));
  out.write(reinterpret_cast<const char*>(index.data()), std::streamsize(h.indexBytes));
  if (!out) return makeError("cannot write '{}'", store.string());
  return {};
}

void swapTilePayloads(StoreSections& sections, std::size_t a, std::size_t b) {
  store_format::IndexRecord& first = sections.index.at(a);
  store_format::IndexRecord& second = sections.index.at(b);
  std::swap(first.payloadOffset, second.payloadOffset);
  std::swap(first.payloadBytes, second.payloadBytes);
  std::swap(first.payloadHash, second.payloadHash);
  std::swap(first.minHeightM, second.minHeightM);
  std::swap(first.maxHeightM, second.maxHeightM);
}

void resealStackHeader(std::string& bytes) {
  std::uint32_t levels = 0;
  std::uint64_t georeferenceBytes = 0;  // version 2: the georeference after the level table
  std::memcpy(&levels, bytes.data() + 12, 4);
  std::memcpy(&georeferenceBytes, bytes.data() + 32, 8);
  std::string checked = bytes.substr(0, 64 + 48 * std::size_t(levels) + std::size_t(georeferenceBytes));
  std::memset(checked.data() + 56, 0, 8);
  const std::uint64_t hash = XXH64(checked.data(), checked.size(), 0);
  std::memcpy(bytes.data() + 56, &hash, 8);
}

BdamParts readBdamParts(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  const std::vector<char> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  BdamParts parts;
  if (bytes.size() < 64) return parts;
  const auto* b = reinterpret_cast<const std::byte*>(bytes.data());
  std::uint32_t count = 0;
  std::memcpy(&count, b + 24, 4);
  const std::size_t tableEnd = std::min(bytes.size(), 64 + std::size_t(count) * 56);
  parts.header.assign(b, b + 64);
  parts.table.assign(b + 64, b + tableEnd);
  parts.data.assign(b + tableEnd, b + bytes.size());
  return parts;
}

void writeBdamParts(BdamParts parts, const std::filesystem::path& file) {
  const std::uint64_t dataStart = parts.header.size() + parts.table.size();
  for (std::size_t at = 0; at + 56 <= parts.table.size(); at += 56) {
    std::uint64_t offset = 0;
    std::uint32_t bytes = 0;
    std::memcpy(&offset, parts.table.data() + at + 8, 8);
    std::memcpy(&bytes, parts.table.data() + at + 16, 4);
    if (offset < dataStart || offset - dataStart + bytes > parts.data.size()) continue;
    const std::uint64_t hash = XXH64(parts.data.data() + (offset - dataStart), bytes, 0);
    std::memcpy(parts.table.data() + at + 48, &hash, 8);
  }
  const std::uint64_t tableHash = XXH64(parts.table.data(), parts.table.size(), 0);
  std::memcpy(parts.header.data() + 44, &tableHash, 8);
  const std::uint64_t headerHash = XXH64(parts.header.data(), 52, 0);
  std::memcpy(parts.header.data() + 52, &headerHash, 8);
  std::ofstream out(file, std::ios::binary | std::ios::trunc);
  for (const auto* part : {&parts.header, &parts.table, &parts.data}) {
    out.write(reinterpret_cast<const char*>(part->data()), std::streamsize(part->size()));
  }
}

}  // namespace tellus::test
