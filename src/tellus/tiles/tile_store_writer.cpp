#include "tellus/tiles/tile_store_writer.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <string>

#include <fmt/format.h>

#include "tellus/core/atomic_output.hpp"
#include "tellus/tiles/store_checksums.hpp"
#include "tellus/tiles/store_format.hpp"

namespace tellus {
namespace fs = std::filesystem;
namespace sf = store_format;

TileStoreWriter::TileStoreWriter(fs::path path, fs::path temporary, int fd, CodecId codec)
    : path_(std::move(path)), temporary_(std::move(temporary)), fd_(fd), codec_(codec) {}

Result<std::unique_ptr<TileStoreWriter>> TileStoreWriter::create(const fs::path& path,
                                                                 CodecId codec) {
  if (Status writable = checkOutputWritable(path); !writable) return writable.error();
  removeStaleTemporariesFor(path);
  const fs::path temporary = temporaryPathFor(path);
  const int fd = ::open(temporary.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  if (fd < 0) {
    return makeError("cannot create '{}': {}", temporary.string(), std::strerror(errno));
  }
  auto writer = std::unique_ptr<TileStoreWriter>(new TileStoreWriter(path, temporary, fd, codec));
  // Room for the header, written by finish().
  const std::array<char, sf::kHeaderBytes> zeros{};
  if (Status s = writer->writeAll(zeros.data(), zeros.size()); !s) return s.error();
  return writer;
}

TileStoreWriter::~TileStoreWriter() {
  if (fd_ >= 0) ::close(fd_);
  if (!finished_) {
    std::error_code ec;
    fs::remove(temporary_, ec);
  }
}

Status TileStoreWriter::writeAll(const void* data, std::size_t bytes) {
  const char* p = static_cast<const char*>(data);
  while (bytes > 0) {
    const ssize_t n = ::write(fd_, p, bytes);
    if (n < 0) {
      if (errno == EINTR) continue;
      return makeError("cannot write '{}': {}", temporary_.string(), std::strerror(errno));
    }
    p += n;
    bytes -= std::size_t(n);
  }
  return {};
}

Status TileStoreWriter::append(TileKey key, std::span<const std::byte> payload,
                               const TileStats& stats) {
  if (finished_) return makeError("store '{}' is already finished", path_.string());
  if (payload.size() > 0xFFFFFFFFu) return makeError("tile payload over 4 GiB");
  TileRecord record;
  record.key = key;
  record.payloadOffset = offset_;
  record.payloadBytes = std::uint32_t(payload.size());
  record.payloadHash = sf::payloadChecksum(payload, key);
  record.stats = stats;
  if (Status s = writeAll(payload.data(), payload.size()); !s) return s;
  offset_ += payload.size();
  records_.push_back(record);
  return {};
}

Status TileStoreWriter::placeWrittenTiles(std::span<const TileRecord> records,
                                          std::uint64_t payloadEnd) {
  if (finished_) return makeError("store '{}' is already finished", path_.string());
  if (payloadEnd < offset_) {
    return makeError("internal error: tiles placed before the end of those appended");
  }
  for (const TileRecord& r : records) {
    if (r.payloadOffset < offset_ || r.payloadOffset + r.payloadBytes > payloadEnd) {
      return makeError("internal error: tile {}/{}/{} placed outside the payloads", r.key.level,
                       r.key.x, r.key.y);
    }
  }
  if (::lseek(fd_, off_t(payloadEnd), SEEK_SET) < 0) {
    return makeError("cannot seek in '{}': {}", temporary_.string(), std::strerror(errno));
  }
  offset_ = payloadEnd;
  records_.insert(records_.end(), records.begin(), records.end());
  return {};
}

void TileStoreWriter::sortRecords() {
  std::sort(records_.begin(), records_.end(), [](const TileRecord& a, const TileRecord& b) {
    return std::tie(a.key.level, a.key.y, a.key.x) < std::tie(b.key.level, b.key.y, b.key.x);
  });
}

Status TileStoreWriter::finish(const StoreMetadata& metadata) {
  const PyramidLayout& layout = metadata.layout;
  sortRecords();
  for (std::size_t i = 0; i < records_.size(); ++i) {
    if (!layout.contains(records_[i].key) || (i > 0 && records_[i].key == records_[i - 1].key)) {
      return makeError("internal error: tile {}/{}/{} outside the pyramid or written twice",
                       records_[i].key.level, records_[i].key.x, records_[i].key.y);
    }
  }
  if (records_.size() != layout.tileCount()) {
    return makeError("internal error: {} tiles written, the pyramid has {}", records_.size(),
                     layout.tileCount());
  }

  return finishWithMetadata(metadataToJson(metadata));
}

Status TileStoreWriter::finishWithMetadata(const std::string& json) {
  if (finished_) return makeError("store '{}' is already finished", path_.string());
  sortRecords();
  std::vector<sf::IndexRecord> index(records_.size());
  for (std::size_t i = 0; i < records_.size(); ++i) {
    const TileRecord& r = records_[i];
    index[i] = {std::uint32_t(r.key.level),
                std::uint32_t(r.key.x),
                std::uint32_t(r.key.y),
                r.payloadBytes,
                r.payloadOffset,
                r.payloadHash,
                r.stats.minHeightM,
                r.stats.maxHeightM,
                r.stats.geometricErrorM,
                r.stats.uncoveredSamples};
  }
  sf::Header header;
  header.codec = std::uint32_t(codec_);
  header.tileCount = std::uint32_t(index.size());
  header.metadataOffset = offset_;
  header.metadataBytes = json.size();
  header.indexOffset = offset_ + json.size();
  header.indexBytes = index.size() * sf::kIndexRecordBytes;
  header.fileBytes = header.indexOffset + header.indexBytes;
  header.metadataHash = sf::sectionChecksum(std::as_bytes(std::span(json.data(), json.size())));
  header.indexHash = sf::sectionChecksum(std::as_bytes(std::span(index)));
  header.headerHash = sf::sectionChecksum(
      std::as_bytes(std::span(&header, 1)).first(offsetof(sf::Header, headerHash)));

  if (Status s = writeAll(json.data(), json.size()); !s) return s;
  if (Status s = writeAll(index.data(), header.indexBytes); !s) return s;
  if (::pwrite(fd_, &header, sizeof(header), 0) != ssize_t(sizeof(header))) {
    return makeError("cannot write the header of '{}': {}", temporary_.string(),
                     std::strerror(errno));
  }
  if (::fsync(fd_) != 0 || ::close(fd_) != 0) {
    fd_ = -1;
    return makeError("cannot flush '{}' to disk: {}", temporary_.string(), std::strerror(errno));
  }
  fd_ = -1;
  // Checked again: the destination may have become something else while the store was built.
  if (Status writable = checkOutputWritable(path_); !writable) return writable;
  std::error_code ec;
  fs::rename(temporary_, path_, ec);
  if (ec) {
    return makeError("cannot move '{}' to '{}': {}", temporary_.string(), path_.string(),
                     ec.message());
  }
  finished_ = true;
  // Make the rename itself durable.
  const fs::path folder = path_.has_parent_path() ? path_.parent_path() : fs::path(".");
  if (const int dir = ::open(folder.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC); dir >= 0) {
    ::fsync(dir);
    ::close(dir);
  }
  return {};
}

}  // namespace tellus
