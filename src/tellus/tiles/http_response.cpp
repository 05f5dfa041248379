#include "tellus/tiles/http_response.hpp"

#include <algorithm>
#include <cctype>
#include <cstring>
#include <limits>

namespace tellus {
namespace {

bool isSpace(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\n'; }

std::string_view trim(std::string_view text) {
  while (!text.empty() && isSpace(text.front())) text.remove_prefix(1);
  while (!text.empty() && isSpace(text.back())) text.remove_suffix(1);
  return text;
}

bool startsWithNoCase(std::string_view text, std::string_view prefix) {
  return text.size() >= prefix.size() &&
         std::equal(prefix.begin(), prefix.end(), text.begin(), [](char a, char b) {
           return std::tolower(static_cast<unsigned char>(a)) == std::tolower(static_cast<unsigned char>(b));
         });
}

// Leading decimal digits of `text` as a number below 2^63; advances `text` past them.
std::optional<std::uint64_t> takeNumber(std::string_view& text) {
  std::size_t digits = 0;
  std::uint64_t value = 0;
  constexpr std::uint64_t kLimit = std::uint64_t(std::numeric_limits<std::int64_t>::max());
  while (digits < text.size() && text[digits] >= '0' && text[digits] <= '9') {
    const std::uint64_t digit = std::uint64_t(text[digits] - '0');
    if (value > (kLimit - digit) / 10) return std::nullopt;
    value = value * 10 + digit;
    ++digits;
  }
  if (digits == 0) return std::nullopt;
  text.remove_prefix(digits);
  return value;
}

// For messages: a header value as printable text of at most 80 characters.
std::string printable(std::string_view text) {
  std::string out;
  for (char c : text.substr(0, 80)) out += (c >= 32 && c < 127) ? c : '?';
  if (text.size() > 80) out += "...";
  return out;
}

}  // namespace

Result<ContentRange> parseContentRange(std::string_view value) {
  std::string_view text = trim(value);
  const auto bad = [&](std::string_view why) {
    return makeError("Content-Range '{}' {}", printable(value), why);
  };
  if (!startsWithNoCase(text, "bytes") || text.size() < 6 || !isSpace(text[5])) {
    return bad("is not 'bytes FIRST-LAST/SIZE'");
  }
  text = trim(text.substr(5));
  ContentRange range;
  std::optional<std::uint64_t> first = takeNumber(text);
  if (!first || text.empty() || text.front() != '-') return bad("is not 'bytes FIRST-LAST/SIZE'");
  text.remove_prefix(1);
  std::optional<std::uint64_t> last = takeNumber(text);
  if (!last || text.empty() || text.front() != '/') return bad("is not 'bytes FIRST-LAST/SIZE'");
  text.remove_prefix(1);
  if (!text.empty() && text.front() == '*') return bad("gives no size ('*')");
  std::optional<std::uint64_t> total = takeNumber(text);
  if (!total || !text.empty()) return bad("is not 'bytes FIRST-LAST/SIZE'");
  if (*last < *first) return bad("ends before it starts");
  if (*last >= *total) return bad("reaches beyond the size it gives");
  range.first = *first;
  range.last = *last;
  range.total = *total;
  return range;
}

void HttpResponseReader::headerLine(std::string_view line) {
  line = trim(line);
  if (startsWithNoCase(line, "HTTP/")) {
    // A new response (the first, or the one after a redirect or a 100 Continue).
    status_ = 0;
    contentRange_.reset();
    const std::size_t space = line.find(' ');
    if (space != std::string_view::npos) {
      std::string_view code = line.substr(space + 1);
      if (std::optional<std::uint64_t> n = takeNumber(code); n && *n >= 100 && *n <= 999) {
        status_ = long(*n);
      }
    }
    return;
  }
  constexpr std::string_view kName = "content-range:";
  if (startsWithNoCase(line, kName)) contentRange_ = std::string(trim(line.substr(kName.size())));
}

std::size_t HttpResponseReader::bodyChunk(const char* data, std::size_t bytes) {
  if (bytes > capacity_ - received_) {
    overflow_ = true;
    return 0;
  }
  if (bytes > 0) std::memcpy(body_ + received_, data, bytes);
  received_ += bytes;
  return bytes;
}

Result<std::uint64_t> HttpResponseReader::finish(long status, std::uint64_t offset,
                                                 std::size_t length) const {
  permanent_ = false;
  if (status == 200) {
    permanent_ = true;
    return makeError("the server does not answer range requests (HTTP 200)");
  }
  if (status != 206) {
    // Client errors stay errors (but a timeout or too many requests may pass); server errors
    // may be transient.
    permanent_ = status >= 400 && status < 500 && status != 408 && status != 429;
    return makeError("HTTP {}", status);
  }
  if (!contentRange_) {
    permanent_ = true;
    return makeError("the server answered 206 without a Content-Range");
  }
  Result<ContentRange> range = parseContentRange(*contentRange_);
  if (!range) {
    permanent_ = true;
    return range.error();
  }
  if (length == 0 || range->first != offset || range->last != offset + length - 1) {
    permanent_ = true;
    return makeError("the server sent bytes {}-{}, not the {}-{} asked for", range->first,
                     range->last, offset, offset + length - 1);
  }
  if (overflow_) return makeError("the server sent more than {} bytes", length);
  if (received_ != length) return makeError("the server sent {} of {} bytes", received_, length);
  return range->total;
}

}  // namespace tellus
