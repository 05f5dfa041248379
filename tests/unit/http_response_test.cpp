// What Tellus makes of an HTTP answer to a range request (tellus/tiles/http_response.hpp),
// without a socket: Content-Range parsing and the verdict on status, headers and body.
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "tellus/tiles/http_response.hpp"

namespace tellus {
namespace {

TEST(ContentRange, ParsesTheOneFormARangeAnswerHas) {
  Result<ContentRange> range = parseContentRange(" bytes 100-199/1000\r\n");
  ASSERT_TRUE(range) << range.error().message;
  EXPECT_EQ(range->first, 100u);
  EXPECT_EQ(range->last, 199u);
  EXPECT_EQ(range->total, 1000u);
  EXPECT_TRUE(parseContentRange("BYTES 0-0/1"));
  for (const char* bad : {"", "bytes", "bytes 1-2", "bytes 1-2/", "bytes 1-2/*", "bytes -1-2/9",
                          "bytes 2-1/9", "bytes 0-9/9", "bytes 0-1/9x", "items 0-1/9", "bytes0-1/9",
                          "bytes 1+2/9", "bytes 0-1/99999999999999999999",
                          "bytes 0-1/18446744073709551615"}) {
    EXPECT_FALSE(parseContentRange(bad)) << "'" << bad << "'";
  }
}

// Feeds `headers` (lines) and `body` to a reader of `capacity` bytes and returns the verdict
// for a request of `length` bytes at `offset`.
struct Verdict {
  Result<std::uint64_t> total;
  bool permanent;
};
Verdict answer(const std::vector<std::string>& headers, const std::string& body, long status,
               std::uint64_t offset, std::size_t length) {
  std::vector<char> buffer(length);
  HttpResponseReader reader(buffer.data(), buffer.size());
  for (const std::string& line : headers) reader.headerLine(line + "\r\n");
  reader.bodyChunk(body.data(), body.size());
  Result<std::uint64_t> total = reader.finish(status, offset, length);
  return {total, reader.permanent()};
}

TEST(HttpResponse, AcceptsExactlyTheBytesAskedFor) {
  const Verdict good = answer({"HTTP/1.1 206 Partial Content", "Content-Range: bytes 10-13/50"},
                              "abcd", 206, 10, 4);
  ASSERT_TRUE(good.total) << good.total.error().message;
  EXPECT_EQ(good.total.value(), 50u);
}

TEST(HttpResponse, SaysWhatTheServerGotWrongAndWhetherRetryingHelps) {
  struct Case {
    std::vector<std::string> headers;
    std::string body;
    long status;
    std::string message;
    bool permanent;
  };
  const std::vector<Case> cases = {
      {{"HTTP/1.1 200 OK"}, "abcd", 200, "does not answer range requests", true},
      {{"HTTP/1.1 404 Not Found"}, "", 404, "HTTP 404", true},
      {{"HTTP/1.1 503 Busy"}, "", 503, "HTTP 503", false},
      {{"HTTP/1.1 429 Slow down"}, "", 429, "HTTP 429", false},
      {{"HTTP/1.1 206 Partial"}, "abcd", 206, "without a Content-Range", true},
      {{"HTTP/1.1 206 Partial", "Content-Range: bytes 0-3/50"}, "abcd", 206, "not the 10-13", true},
      {{"HTTP/1.1 206 Partial", "Content-Range: bytes 10-13/*"}, "abcd", 206, "gives no size", true},
      {{"HTTP/1.1 206 Partial", "Content-Range: bytes 10-13/50"}, "ab", 206, "sent 2 of 4 bytes", false},
      {{"HTTP/1.1 206 Partial", "Content-Range: bytes 10-13/50"}, "abcdef", 206, "more than 4 bytes", false},
  };
  for (const Case& c : cases) {
    const Verdict v = answer(c.headers, c.body, c.status, 10, 4);
    ASSERT_FALSE(v.total) << c.message;
    EXPECT_NE(v.total.error().message.find(c.message), std::string::npos) << v.total.error().message;
    EXPECT_EQ(v.permanent, c.permanent) << c.message;
  }
}

TEST(HttpResponse, ARedirectsHeadersAreForgottenWithItsResponse) {
  // The redirect said Content-Range; the final answer did not: no range to trust.
  std::vector<char> buffer(4);
  HttpResponseReader reader(buffer.data(), buffer.size());
  reader.headerLine("HTTP/1.1 302 Found\r\n");
  reader.headerLine("Content-Range: bytes 10-13/50\r\n");
  reader.headerLine("Location: /elsewhere\r\n");
  reader.headerLine("HTTP/1.1 206 Partial Content\r\n");
  EXPECT_EQ(reader.statusFromHeaders(), 206);
  reader.bodyChunk("abcd", 4);
  Result<std::uint64_t> total = reader.finish(206, 10, 4);
  ASSERT_FALSE(total);
  EXPECT_NE(total.error().message.find("without a Content-Range"), std::string::npos);
}

}  // namespace
}  // namespace tellus
