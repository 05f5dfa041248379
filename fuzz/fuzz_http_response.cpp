// libFuzzer target: what Tellus makes of an HTTP answer to a range request
// (tellus/tiles/http_response.hpp), without a socket: status lines, headers (Content-Range
// above all, redirects' headers before the final answer's), bodies shorter or longer than
// promised. Input: [offset u32][length u16][header lines, '\n' each, up to an empty line][body].
// The verdict must be an error or exactly the bytes asked for with a size beyond them.
#include <algorithm>
#include <cstdint>
#include <cstdlib>
#include <string_view>
#include <vector>

#include "fuzz_input.hpp"
#include "tellus/tiles/http_response.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  tellus::fuzz::FuzzInput input(data, size);
  const std::uint64_t offset = input.take<std::uint32_t>();
  const std::size_t length = 1 + input.take<std::uint16_t>() % 4096;
  const std::span<const std::byte> rest = input.rest();
  std::string_view text(reinterpret_cast<const char*>(rest.data()), rest.size());
  static std::vector<char> body;
  body.assign(length, 0);
  tellus::HttpResponseReader reader(body.data(), body.size());
  // Header lines as the transport hands them over, one at a time, up to the blank line.
  while (!text.empty()) {
    const std::size_t end = text.find('\n');
    const std::string_view line = text.substr(0, end == std::string_view::npos ? text.size() : end + 1);
    text.remove_prefix(line.size());
    if (line == "\n" || line == "\r\n") break;
    reader.headerLine(line);
    (void)tellus::parseContentRange(line);
  }
  // The body in chunks of up to 1000 bytes, as a socket delivers it.
  while (!text.empty()) {
    const std::size_t chunk = std::min<std::size_t>(text.size(), 1000);
    if (reader.bodyChunk(text.data(), chunk) != chunk) break;
    text.remove_prefix(chunk);
  }
  tellus::Result<std::uint64_t> total = reader.finish(reader.statusFromHeaders(), offset, length);
  if (total && (reader.received() != length || total.value() < offset + length)) std::abort();
  return 0;
}
