#pragma once
// Where a store's bytes come from: a local file (pread) or an http:// or https:// URL (range
// requests, http_byte_source.hpp). Readers (store_container.hpp) see only exact reads at
// offsets, so a store streams over HTTP with the same checks (sizes, checksums) as from disk.
// Thread-safe: reads may come from many threads at once.
#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <string_view>

#include "tellus/core/result.hpp"

namespace tellus {

class ByteSource {
 public:
  virtual ~ByteSource() = default;
  // Reads exactly `bytes` at `offset`; an error says why (and, for URLs, after what retries).
  virtual Status readAt(void* data, std::size_t bytes, std::uint64_t offset) const = 0;
  virtual std::uint64_t size() const = 0;
  // The file's path or the URL, for messages.
  virtual const std::string& name() const = 0;
  // True when reads fail at once because an earlier one found the source dead (a server that
  // stopped answering): callers that read many pieces (verify) stop instead of waiting on each.
  virtual bool failing() const { return false; }
};

// True for "http://..." and "https://..." (case-insensitive scheme).
bool isUrl(std::string_view location);

// Opens a regular local file (a FIFO or device is refused, never waited on) or a URL.
Result<std::shared_ptr<ByteSource>> openByteSource(const std::string& location);

}  // namespace tellus
