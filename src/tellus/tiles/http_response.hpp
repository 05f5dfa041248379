#pragma once
// What Tellus makes of one HTTP answer to a range request, apart from the socket (libcurl does
// the transport): the header lines as they arrive (one response after another when redirects
// are followed), the body into a fixed buffer, and the verdict. Kept free of libcurl so that a
// fuzzer can feed it any bytes (fuzz/fuzz_http_response.cpp).
//
// A range request for bytes [offset, offset + length) is answered well only by a 206 whose
// Content-Range is "bytes offset-(offset+length-1)/TOTAL" with TOTAL beyond the range, and a
// body of exactly `length` bytes. Anything else is an error saying what the server sent;
// `permanent` marks those that retrying cannot mend (200: no range support; 4xx but 408 and
// 429; a Content-Range for other bytes than asked).
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

#include "tellus/core/result.hpp"

namespace tellus {

struct ContentRange {
  std::uint64_t first = 0, last = 0;  // inclusive byte positions
  std::uint64_t total = 0;            // the file's size
};

// Parses a Content-Range header value: "bytes FIRST-LAST/TOTAL" (whitespace around tolerated,
// the unit case-insensitive). Refuses "*" for a size, LAST < FIRST, LAST >= TOTAL, numbers with
// signs or beyond 2^63, and any trailing text.
Result<ContentRange> parseContentRange(std::string_view value);

class HttpResponseReader {
 public:
  // The body goes into `body` (`capacity` bytes); more than that is an overflow, not a write.
  HttpResponseReader(void* body, std::size_t capacity) : body_(static_cast<char*>(body)), capacity_(capacity) {}

  // One header line as the transport gives it (with or without its CR LF). A status line
  // ("HTTP/1.1 206 Partial Content") starts a new response: what an earlier one (a redirect)
  // said is forgotten.
  void headerLine(std::string_view line);
  // Body bytes; returns how many were taken (fewer than given stops the transfer).
  std::size_t bodyChunk(const char* data, std::size_t bytes);

  // The verdict for a request of `length` bytes at `offset`, given the final HTTP status
  // (the transport's, or statusFromHeaders() without one). On success, the file's size.
  Result<std::uint64_t> finish(long status, std::uint64_t offset, std::size_t length) const;
  // True after finish() failed in a way retrying cannot mend.
  bool permanent() const { return permanent_; }

  long statusFromHeaders() const { return status_; }
  bool overflowed() const { return overflow_; }
  std::size_t received() const { return received_; }

 private:
  char* body_;
  std::size_t capacity_;
  std::size_t received_ = 0;
  bool overflow_ = false;
  long status_ = 0;
  std::optional<std::string> contentRange_;  // the raw value of the last response's header
  mutable bool permanent_ = false;
};

}  // namespace tellus
