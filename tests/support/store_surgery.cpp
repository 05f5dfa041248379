#include "support/store_surgery.hpp"

#include <cstring>
#include <fstream>
#include <iterator>

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

}  // namespace tellus::test
