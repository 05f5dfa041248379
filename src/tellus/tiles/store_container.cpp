#include "tellus/tiles/store_container.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstddef>
#include <cstring>

#include <nlohmann/json.hpp>

#include "tellus/core/input_file.hpp"
#include "tellus/tiles/store_checksums.hpp"

namespace tellus {
namespace fs = std::filesystem;
namespace sf = store_format;

Status preadExact(int fd, void* data, std::size_t bytes, std::uint64_t offset) {
  char* p = static_cast<char*>(data);
  while (bytes > 0) {
    const ssize_t n = ::pread(fd, p, bytes, off_t(offset));
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) return makeError("read failed: {}", std::strerror(errno));
    if (n == 0) return makeError("unexpected end of file");
    p += n;
    bytes -= std::size_t(n);
    offset += std::uint64_t(n);
  }
  return {};
}

namespace {

Status readSections(StoreContainer& c, const std::string& name) {
  c.fileBytes = c.source->size();
  sf::Header& header = c.header;
  if (c.fileBytes < sf::kHeaderBytes || !c.source->readAt(&header, sizeof(header), 0)) {
    return makeError("'{}' is not a tile store: too short for a header", name);
  }
  if (header.magic != sf::kMagic) return makeError("'{}' is not a tile store (bad magic)", name);
  const std::uint64_t headerHash = sf::sectionChecksum(
      std::as_bytes(std::span(&header, 1)).first(offsetof(sf::Header, headerHash)));
  if (!sf::checksumMatches(headerHash, header.headerHash)) {
    return makeError("'{}' has a corrupt header (checksum mismatch)", name);
  }
  if (header.version == 1) {
    return makeError(
        "'{}' is a version 1 tile store, written before tile keys were bound into its "
        "checksums; rebuild it with 'tellus build'",
        name);
  }
  if (header.version != sf::kVersion) {
    return makeError("'{}' is a version {} tile store; this Tellus reads version {}", name,
                     header.version, sf::kVersion);
  }
  if (header.fileBytes != c.fileBytes) {
    return makeError("'{}' is truncated or padded: {} bytes, the header says {}", name,
                     c.fileBytes, header.fileBytes);
  }
  const std::uint64_t end = c.fileBytes;
  if (header.headerBytes != sf::kHeaderBytes || header.metadataOffset < sf::kHeaderBytes ||
      header.metadataOffset > end || header.metadataBytes > end - header.metadataOffset ||
      header.indexOffset != header.metadataOffset + header.metadataBytes ||
      header.indexBytes != std::uint64_t(header.tileCount) * sf::kIndexRecordBytes ||
      header.indexBytes > end - header.indexOffset) {
    return makeError("'{}' has an inconsistent header (sections outside the file)", name);
  }
  c.metadataJson.assign(header.metadataBytes, '\0');
  if (Status s = c.source->readAt(c.metadataJson.data(), c.metadataJson.size(),
                            header.metadataOffset);
      !s) {
    return makeError("cannot read the metadata of '{}': {}", name, s.error().message);
  }
  if (!sf::checksumMatches(
          sf::sectionChecksum(std::as_bytes(std::span(c.metadataJson.data(), c.metadataJson.size()))),
          header.metadataHash)) {
    return makeError("'{}' has corrupt metadata (checksum mismatch)", name);
  }
  c.index.resize(header.tileCount);
  if (Status s = c.source->readAt(c.index.data(), header.indexBytes, header.indexOffset); !s) {
    return makeError("cannot read the tile index of '{}': {}", name, s.error().message);
  }
  if (!sf::checksumMatches(sf::sectionChecksum(std::as_bytes(std::span(c.index))),
                          header.indexHash)) {
    return makeError("'{}' has a corrupt tile index (checksum mismatch)", name);
  }
  return {};
}

}  // namespace

Result<StoreContainer> readStoreContainer(const std::string& location) {
  Result<std::shared_ptr<ByteSource>> source = openByteSource(location);
  if (!source) return source.error();
  StoreContainer c;
  c.source = std::move(source.value());
  if (Status s = readSections(c, location); !s) return s.error();
  return c;
}

namespace {

// Reads the top-level "format" of a JSON object and stops there: every store open asks it
// first, and the whole metadata (every level's figures) need not become a document for that.
class FormatFinder : public nlohmann::json::json_sax_t {
 public:
  std::string format;

  bool null() override { return value(); }
  bool boolean(bool) override { return value(); }
  bool number_integer(number_integer_t) override { return value(); }
  bool number_unsigned(number_unsigned_t) override { return value(); }
  bool number_float(number_float_t, const string_t&) override { return value(); }
  bool string(string_t& text) override {
    if (depth_ == 1 && formatNext_) {
      format = text;
      return false;  // found: stop parsing
    }
    return value();
  }
  bool binary(binary_t&) override { return value(); }
  bool start_object(std::size_t) override { return enter(); }
  bool end_object() override { return leave(); }
  bool start_array(std::size_t) override { return enter(); }
  bool end_array() override { return leave(); }
  bool key(string_t& name) override {
    formatNext_ = depth_ == 1 && name == "format";
    return true;
  }
  bool parse_error(std::size_t, const std::string&, const nlohmann::json::exception&) override {
    return false;
  }

 private:
  // A value other than the format's string: when it was the format's, there is none.
  bool value() { return !(depth_ == 1 && formatNext_); }
  bool enter() {
    if (depth_ == 0 && started_) return false;  // only the first top-level value counts
    if (depth_ == 1 && formatNext_) return false;
    started_ = true;
    ++depth_;
    return true;
  }
  bool leave() {
    --depth_;
    return depth_ > 0;  // the top-level object closed without a format
  }
  int depth_ = 0;
  bool started_ = false;
  bool formatNext_ = false;
};

}  // namespace

std::string storeFormatName(std::string_view metadataJson) {
  FormatFinder finder;
  nlohmann::json::sax_parse(metadataJson, &finder, nlohmann::json::input_format_t::json, false);
  return finder.format;
}

bool payloadInsideFile(const sf::IndexRecord& r, const sf::Header& header) {
  return r.payloadOffset >= sf::kHeaderBytes && r.payloadOffset <= header.metadataOffset &&
         r.payloadBytes <= header.metadataOffset - r.payloadOffset;
}

Status readCheckedPayload(const ByteSource& source, const TileRecord& record,
                          const std::string& describe, std::vector<std::byte>& payload) {
  payload.resize(record.payloadBytes);
  if (Status s = source.readAt(payload.data(), payload.size(), record.payloadOffset); !s) {
    return makeError("'{}': cannot read {}: {}", source.name(), describe, s.error().message);
  }
  if (!sf::checksumMatches(sf::payloadChecksum(payload, record.key), record.payloadHash)) {
    return makeError("'{}': {} is corrupt (checksum mismatch)", source.name(), describe);
  }
  return {};
}

}  // namespace tellus
