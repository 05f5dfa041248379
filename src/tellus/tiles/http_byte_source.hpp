#pragma once
// A store's bytes over HTTP(S) with libcurl: every read is one range request
// ("Range: bytes=a-b", answered 206 with exactly those bytes, http_response.hpp), on
// connections kept alive in a small pool. Transient failures (no connection, timeouts, 5xx,
// 429, short bodies) are retried with exponential back-off within one deadline for the whole
// read; the error after it names the URL, the range and the cause. The size comes from the
// first request's Content-Range. Thread-safe.
//
// No read waits for ever: a try ends when the server sends less than lowSpeedBytes a second
// for lowSpeedSeconds (a silent or trickling server), at timeoutMs, or when the read's deadline
// passes; redirects are followed at most maxRedirects times. A URL whose read failed that way
// (or that loops in redirects) is not asked again for coolDownMs, in this process (every
// source of that URL): later reads fail at once with the first error, so a dead server costs
// one deadline, not one per tile or per open. A 404 or a server without ranges is not
// remembered: asking again costs nothing and may succeed once the file is there.
//
// Limits, overridable by the environment (tests, slow links) or the command line
// (setProcessDefaults(), tellus --http-deadline / --http-retries):
//   TELLUS_HTTP_RETRIES         retries after the first try (default 3)
//   TELLUS_HTTP_DEADLINE_MS     a read, all its tries together (default 25000)
//   TELLUS_HTTP_TIMEOUT_MS      one try (default 20000)
//   TELLUS_HTTP_CONNECT_MS      connection timeout (default 3000)
//   TELLUS_HTTP_BACKOFF_MS      first retry delay, doubled each retry (default 100)
//   TELLUS_HTTP_LOW_SPEED_BPS   bytes a second below which a try is stalled (default 1024)
//   TELLUS_HTTP_LOW_SPEED_S     seconds of stall that end a try (default 8)
//   TELLUS_HTTP_MAX_REDIRECTS   redirects followed (default 10)
//   TELLUS_HTTP_COOLDOWN_MS     how long a failed URL is not asked again (default 30000)
#include <atomic>
#include <mutex>
#include <vector>

#include "tellus/tiles/byte_source.hpp"

namespace tellus {

struct HttpSourceOptions {
  int retries = 3;
  long deadlineMs = 25000;
  long timeoutMs = 20000;
  long connectTimeoutMs = 3000;
  long backoffMs = 100;
  long lowSpeedBytesPerSecond = 1024;
  long lowSpeedSeconds = 8;
  long maxRedirects = 10;
  long coolDownMs = 30000;
  // The process defaults (setProcessDefaults(), else the built-in ones), then the environment.
  static HttpSourceOptions fromEnvironment();
  // Replaces the defaults fromEnvironment() starts from (the command line's options).
  static void setProcessDefaults(const HttpSourceOptions& defaults);
  static HttpSourceOptions processDefaults();
};

class HttpByteSource final : public ByteSource {
 public:
  static Result<std::shared_ptr<HttpByteSource>> open(
      const std::string& url, HttpSourceOptions options = HttpSourceOptions::fromEnvironment());
  ~HttpByteSource() override;

  Status readAt(void* data, std::size_t bytes, std::uint64_t offset) const override;
  std::uint64_t size() const override { return size_; }
  const std::string& name() const override { return url_; }
  // True while the URL is cooling down after a failed read (reads fail at once).
  bool failing() const override;

  std::uint64_t requests() const { return requests_.load(); }  // tries, retries included
  std::uint64_t retries() const { return retries_.load(); }
  std::uint64_t bytesRead() const { return bytesRead_.load(); }

  // Forgets every URL's failure (tests).
  static void forgetFailures();

 private:
  HttpByteSource() = default;
  // One try: the bytes [offset, offset + bytes) into `data`, within `timeoutMs`; `permanent`
  // is set when retrying cannot help (404, 416, a server without range support, too many
  // redirects), `remember` when another read of the URL would not fare better either (a
  // redirect loop). `totalSize` receives the size from Content-Range when not null.
  Status tryRead(void* data, std::size_t bytes, std::uint64_t offset, long timeoutMs,
                 bool& permanent, bool& remember, std::uint64_t* totalSize) const;
  // The URL is not asked again for the cool-down: later reads fail at once with `error`.
  void rememberFailure(const Error& error) const;
  // tryRead, retried with back-off while the failure may be transient and the deadline allows.
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
