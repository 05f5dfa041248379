#include "tellus/tiles/http_byte_source.hpp"

#include <curl/curl.h>

#include <chrono>
#include <cstdlib>
#include <cstring>
#include <string>
#include <thread>

namespace tellus {
namespace {

void initialiseCurlOnce() {
  static std::once_flag once;
  std::call_once(once, [] { curl_global_init(CURL_GLOBAL_DEFAULT); });
}

long environmentNumber(const char* name, long fallback, long lo, long hi) {
  const char* text = std::getenv(name);
  if (!text || !*text) return fallback;
  char* end = nullptr;
  const long value = std::strtol(text, &end, 10);
  if (*end != '\0' || value < lo || value > hi) return fallback;
  return value;
}

// Receives the body into a fixed buffer; more than it holds aborts the transfer.
struct BodySink {
  char* data = nullptr;
  std::size_t capacity = 0;
  std::size_t received = 0;
  bool overflow = false;
};

std::size_t writeBody(char* chunk, std::size_t size, std::size_t count, void* user) {
  auto* sink = static_cast<BodySink*>(user);
  const std::size_t n = size * count;
  if (sink->received + n > sink->capacity) {
    sink->overflow = true;
    return 0;  // aborts with CURLE_WRITE_ERROR
  }
  std::memcpy(sink->data + sink->received, chunk, n);
  sink->received += n;
  return n;
}

// Picks the total size out of "Content-Range: bytes a-b/TOTAL".
std::size_t readHeader(char* line, std::size_t size, std::size_t count, void* user) {
  const std::size_t n = size * count;
  std::string text(line, n);
  constexpr std::string_view kName = "content-range:";
  if (text.size() > kName.size() &&
      std::equal(kName.begin(), kName.end(), text.begin(),
                 [](char a, char b) { return a == std::tolower(static_cast<unsigned char>(b)); })) {
    const std::size_t slash = text.find('/');
    if (slash != std::string::npos) {
      *static_cast<std::uint64_t*>(user) = std::strtoull(text.c_str() + slash + 1, nullptr, 10);
    }
  }
  return n;
}

}  // namespace

HttpSourceOptions HttpSourceOptions::fromEnvironment() {
  HttpSourceOptions o;
  o.retries = int(environmentNumber("TELLUS_HTTP_RETRIES", o.retries, 0, 100));
  o.timeoutMs = environmentNumber("TELLUS_HTTP_TIMEOUT_MS", o.timeoutMs, 1, 3'600'000);
  o.connectTimeoutMs = environmentNumber("TELLUS_HTTP_CONNECT_MS", o.connectTimeoutMs, 1, 600'000);
  o.backoffMs = environmentNumber("TELLUS_HTTP_BACKOFF_MS", o.backoffMs, 0, 60'000);
  return o;
}

Result<std::shared_ptr<HttpByteSource>> HttpByteSource::open(const std::string& url,
                                                             HttpSourceOptions options) {
  initialiseCurlOnce();
  std::shared_ptr<HttpByteSource> source(new HttpByteSource());
  source->url_ = url;
  source->options_ = options;
  // The first byte, for the size (Content-Range) and to learn that ranges are served.
  char first = 0;
  std::uint64_t total = 0;
  const Status status = source->readWithRetries(&first, 1, 0, &total);
  if (!status) return status.error();
  if (total == 0) {
    return makeError("'{}': the server gave no size (Content-Range) for a range request", url);
  }
  source->size_ = total;
  return source;
}

HttpByteSource::~HttpByteSource() {
  for (void* handle : pool_) curl_easy_cleanup(static_cast<CURL*>(handle));
}

void* HttpByteSource::takeHandle() const {
  {
    std::lock_guard lock(poolMutex_);
    if (!pool_.empty()) {
      void* handle = pool_.back();
      pool_.pop_back();
      return handle;
    }
  }
  return curl_easy_init();
}

void HttpByteSource::returnHandle(void* handle) const {
  std::lock_guard lock(poolMutex_);
  pool_.push_back(handle);
}

Status HttpByteSource::tryRead(void* data, std::size_t bytes, std::uint64_t offset,
                               bool& permanent, std::uint64_t* totalSize) const {
  CURL* curl = static_cast<CURL*>(takeHandle());
  if (!curl) return makeError("'{}': libcurl could not make a request", url_);
  ++requests_;
  BodySink sink{static_cast<char*>(data), bytes, 0, false};
  std::uint64_t total = 0;
  const std::string range = fmt::format("{}-{}", offset, offset + bytes - 1);
  curl_easy_reset(curl);
  curl_easy_setopt(curl, CURLOPT_URL, url_.c_str());
  curl_easy_setopt(curl, CURLOPT_RANGE, range.c_str());
  curl_easy_setopt(curl, CURLOPT_NOSIGNAL, 1L);
  curl_easy_setopt(curl, CURLOPT_FOLLOWLOCATION, 1L);
  curl_easy_setopt(curl, CURLOPT_TIMEOUT_MS, options_.timeoutMs);
  curl_easy_setopt(curl, CURLOPT_CONNECTTIMEOUT_MS, options_.connectTimeoutMs);
  curl_easy_setopt(curl, CURLOPT_USERAGENT, "tellus/" TELLUS_VERSION);
  curl_easy_setopt(curl, CURLOPT_WRITEFUNCTION, writeBody);
  curl_easy_setopt(curl, CURLOPT_WRITEDATA, &sink);
  curl_easy_setopt(curl, CURLOPT_HEADERFUNCTION, readHeader);
  curl_easy_setopt(curl, CURLOPT_HEADERDATA, &total);
  const CURLcode code = curl_easy_perform(curl);
  long httpStatus = 0;
  curl_easy_getinfo(curl, CURLINFO_RESPONSE_CODE, &httpStatus);
  returnHandle(curl);

  const std::string what = fmt::format("'{}': cannot read {} bytes at {}", url_, bytes, offset);
  permanent = false;
  if (code != CURLE_OK && !(code == CURLE_WRITE_ERROR && sink.overflow)) {
    return makeError("{}: {}", what, curl_easy_strerror(code));
  }
  if (httpStatus == 200) {
    permanent = true;
    return makeError("{}: the server does not answer range requests (HTTP 200)", what);
  }
  if (httpStatus != 206) {
    // Client errors stay errors (but a timeout or too many requests may pass); server errors
    // may be transient.
    permanent = httpStatus >= 400 && httpStatus < 500 && httpStatus != 408 && httpStatus != 429;
    return makeError("{}: HTTP {}", what, httpStatus);
  }
  if (sink.overflow || sink.received != bytes) {
    return makeError("{}: the server sent {} bytes", what,
                     sink.overflow ? fmt::format("more than {}", bytes) : std::to_string(sink.received));
  }
  if (totalSize) *totalSize = total;
  bytesRead_ += bytes;
  return {};
}

Status HttpByteSource::readAt(void* data, std::size_t bytes, std::uint64_t offset) const {
  if (bytes == 0) return {};
  return readWithRetries(data, bytes, offset, nullptr);
}

Status HttpByteSource::readWithRetries(void* data, std::size_t bytes, std::uint64_t offset,
                                       std::uint64_t* totalSize) const {
  Status status;
  for (int attempt = 0; attempt <= options_.retries; ++attempt) {
    bool permanent = false;
    status = tryRead(data, bytes, offset, permanent, totalSize);
    if (status || permanent) return status;
    if (attempt < options_.retries) {
      ++retries_;
      std::this_thread::sleep_for(std::chrono::milliseconds(options_.backoffMs << attempt));
    }
  }
  return makeError("{} (after {} tries)", status.error().message, options_.retries + 1);
}

}  // namespace tellus
