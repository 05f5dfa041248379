#pragma once
// A store's bytes over HTTP(S) with libcurl: every read is one range request
// ("Range: bytes=a-b", answered 206 with exactly those bytes), on connections kept alive in a
// small pool. Transient failures (no connection, timeouts, 5xx, 429, short bodies) are retried
// with exponential back-off; the error after the last try names the URL, the range and the
// cause. The size comes from the first request's Content-Range. Thread-safe.
//
// Limits, overridable by the environment (tests, slow links):
//   TELLUS_HTTP_RETRIES      retries after the first try (default 3)
//   TELLUS_HTTP_TIMEOUT_MS   whole-request timeout (default 20000)
//   TELLUS_HTTP_CONNECT_MS   connection timeout (default 3000)
//   TELLUS_HTTP_BACKOFF_MS   first retry delay, doubled each retry (default 100)
#include <atomic>
#include <mutex>
#include <vector>

#include "tellus/tiles/byte_source.hpp"

namespace tellus {

struct HttpSourceOptions {
  int retries = 3;
  long timeoutMs = 20000;
  long connectTimeoutMs = 3000;
  long backoffMs = 100;
  static HttpSourceOptions fromEnvironment();
};

class HttpByteSource final : public ByteSource {
 public:
  static Result<std::shared_ptr<HttpByteSource>> open(
      const std::string& url, HttpSourceOptions options = HttpSourceOptions::fromEnvironment());
  ~HttpByteSource() override;

  Status readAt(void* data, std::size_t bytes, std::uint64_t offset) const override;
  std::uint64_t size() const override { return size_; }
  const std::string& name() const override { return url_; }

  std::uint64_t requests() const { return requests_.load(); }  // tries, retries included
  std::uint64_t retries() const { return retries_.load(); }
  std::uint64_t bytesRead() const { return bytesRead_.load(); }

 private:
  HttpByteSource() = default;
  // One try: the bytes [offset, offset + bytes) into `data`; `permanent` is set when retrying
  // cannot help (404, 416, a server without range support). `totalSize` receives the size from
  // Content-Range when not null.
  Status tryRead(void* data, std::size_t bytes, std::uint64_t offset, bool& permanent,
                 std::uint64_t* totalSize) const;
  // tryRead, retried with back-off while the failure may be transient.
  Status readWithRetries(void* data, std::size_t bytes, std::uint64_t offset,
                         std::uint64_t* totalSize) const;
  void* takeHandle() const;
  void returnHandle(void* handle) const;

  std::string url_;
  HttpSourceOptions options_;
  std::uint64_t size_ = 0;
  mutable std::mutex poolMutex_;
  mutable std::vector<void*> pool_;  // idle CURL easy handles
  mutable std::atomic<std::uint64_t> requests_{0}, retries_{0}, bytesRead_{0};
};

}  // namespace tellus
