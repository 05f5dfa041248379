#include "tellus/tiles/http_byte_source.hpp"

#include <curl/curl.h>

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <map>
#include <string>
#include <thread>

#include "tellus/tiles/http_response.hpp"

namespace tellus {
namespace {

using Clock = std::chrono::steady_clock;

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

std::size_t writeBody(char* chunk, std::size_t size, std::size_t count, void* user) {
  // Fewer bytes taken than given aborts the transfer with CURLE_WRITE_ERROR.
  return static_cast<HttpResponseReader*>(user)->bodyChunk(chunk, size * count);
}

std::size_t readHeader(char* line, std::size_t size, std::size_t count, void* user) {
  static_cast<HttpResponseReader*>(user)->headerLine(std::string_view(line, size * count));
  return size * count;
}

// URLs whose read failed for want of an answer, with when and why: not asked again until then.
struct FailedUrls {
  std::mutex mutex;
  std::map<std::string, std::pair<Clock::time_point, std::string>> failures;  // until, error
};
FailedUrls& failedUrls() {
  static FailedUrls urls;
  return urls;
}

std::mutex defaultsMutex;
HttpSourceOptions& processDefaultsStorage() {
  static HttpSourceOptions defaults;
  return defaults;
}

}  // namespace

void HttpSourceOptions::setProcessDefaults(const HttpSourceOptions& defaults) {
  std::lock_guard lock(defaultsMutex);
  processDefaultsStorage() = defaults;
}

HttpSourceOptions HttpSourceOptions::processDefaults() {
  std::lock_guard lock(defaultsMutex);
  return processDefaultsStorage();
}

HttpSourceOptions HttpSourceOptions::fromEnvironment() {
  HttpSourceOptions o = processDefaults();
  o.retries = int(environmentNumber("TELLUS_HTTP_RETRIES", o.retries, 0, 100));
  o.deadlineMs = environmentNumber("TELLUS_HTTP_DEADLINE_MS", o.deadlineMs, 1, 86'400'000);
  o.timeoutMs = environmentNumber("TELLUS_HTTP_TIMEOUT_MS", o.timeoutMs, 1, 3'600'000);
  o.connectTimeoutMs = environmentNumber("TELLUS_HTTP_CONNECT_MS", o.connectTimeoutMs, 1, 600'000);
  o.backoffMs = environmentNumber("TELLUS_HTTP_BACKOFF_MS", o.backoffMs, 0, 60'000);
  o.lowSpeedBytesPerSecond =
      environmentNumber("TELLUS_HTTP_LOW_SPEED_BPS", o.lowSpeedBytesPerSecond, 0, 1'000'000'000);
  o.lowSpeedSeconds = environmentNumber("TELLUS_HTTP_LOW_SPEED_S", o.lowSpeedSeconds, 1, 3600);
  o.maxRedirects = environmentNumber("TELLUS_HTTP_MAX_REDIRECTS", o.maxRedirects, 0, 100);
  o.coolDownMs = environmentNumber("TELLUS_HTTP_COOLDOWN_MS", o.coolDownMs, 0, 86'400'000);
  return o;
}

void HttpByteSource::forgetFailures() {
  FailedUrls& urls = failedUrls();
  std::lock_guard lock(urls.mutex);
  urls.failures.clear();
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
  source->size_ = total;
  return source;
}

HttpByteSource::~HttpByteSource() {
  for (void* handle : pool_) curl_easy_cleanup(static_cast<CURL*>(handle));
}

bool HttpByteSource::failing() const {
  FailedUrls& urls = failedUrls();
  std::lock_guard lock(urls.mutex);
  const auto it = urls.failures.find(url_);
  return it != urls.failures.end() && Clock::now() < it->second.first;
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

Status HttpByteSource::tryRead(void* data, std::size_t bytes, std::uint64_t offset, long timeoutMs,
                               bool& permanent, bool& remember, std::uint64_t* totalSize) const {
  remember = false;
  CURL* curl = static_cast<CURL*>(takeHandle());
  if (!curl) return makeError("'{}': libcurl could not make a request", url_);
  ++requests_;
  HttpResponseReader response(data, bytes);
  const std::string range = fmt::format("{}-{}", offset, offset + bytes - 1);
  curl_easy_reset(curl);
  curl_easy_setopt(curl, CURLOPT_URL, url_.c_str());
  curl_easy_setopt(curl, CURLOPT_RANGE, range.c_str());
  curl_easy_setopt(curl, CURLOPT_NOSIGNAL, 1L);
  curl_easy_setopt(curl, CURLOPT_FOLLOWLOCATION, 1L);
  curl_easy_setopt(curl, CURLOPT_MAXREDIRS, options_.maxRedirects);
  curl_easy_setopt(curl, CURLOPT_TIMEOUT_MS, timeoutMs);
  curl_easy_setopt(curl, CURLOPT_CONNECTTIMEOUT_MS, std::min(options_.connectTimeoutMs, timeoutMs));
  if (options_.lowSpeedBytesPerSecond > 0) {
    curl_easy_setopt(curl, CURLOPT_LOW_SPEED_LIMIT, options_.lowSpeedBytesPerSecond);
    curl_easy_setopt(curl, CURLOPT_LOW_SPEED_TIME, options_.lowSpeedSeconds);
  }
  curl_easy_setopt(curl, CURLOPT_USERAGENT, "tellus/" TELLUS_VERSION);
  curl_easy_setopt(curl, CURLOPT_WRITEFUNCTION, writeBody);
  curl_easy_setopt(curl, CURLOPT_WRITEDATA, &response);
  curl_easy_setopt(curl, CURLOPT_HEADERFUNCTION, readHeader);
  curl_easy_setopt(curl, CURLOPT_HEADERDATA, &response);
  const CURLcode code = curl_easy_perform(curl);
  long httpStatus = 0;
  curl_easy_getinfo(curl, CURLINFO_RESPONSE_CODE, &httpStatus);
  returnHandle(curl);

  const std::string what = fmt::format("'{}': cannot read {} bytes at {}", url_, bytes, offset);
  permanent = false;
  if (code == CURLE_TOO_MANY_REDIRECTS) {
    permanent = true;
    remember = true;  // a misconfigured server: asking again (another open) loops again
    return makeError("{}: more than {} redirects (a redirect loop?)", what, options_.maxRedirects);
  }
  if (code == CURLE_OPERATION_TIMEDOUT && response.received() == 0 && httpStatus == 0) {
    return makeError("{}: the server does not answer", what);
  }
  if (code == CURLE_OPERATION_TIMEDOUT) {
    return makeError("{}: the transfer stalled (under {} bytes a second)", what,
                     options_.lowSpeedBytesPerSecond);
  }
  if (code != CURLE_OK && !(code == CURLE_WRITE_ERROR && response.overflowed())) {
    return makeError("{}: {}", what, curl_easy_strerror(code));
  }
  Result<std::uint64_t> total = response.finish(httpStatus, offset, bytes);
  if (!total) {
    permanent = response.permanent();
    return makeError("{}: {}", what, total.error().message);
  }
  if (totalSize) *totalSize = total.value();
  bytesRead_ += bytes;
  return {};
}

Status HttpByteSource::readAt(void* data, std::size_t bytes, std::uint64_t offset) const {
  if (bytes == 0) return {};
  return readWithRetries(data, bytes, offset, nullptr);
}

Status HttpByteSource::readWithRetries(void* data, std::size_t bytes, std::uint64_t offset,
                                       std::uint64_t* totalSize) const {
  FailedUrls& urls = failedUrls();
  {
    std::lock_guard lock(urls.mutex);
    const auto it = urls.failures.find(url_);
    // The first failure's message: the server was given its deadline once already.
    if (it != urls.failures.end() && Clock::now() < it->second.first) return Error{it->second.second};
  }
  const Clock::time_point start = Clock::now();
  const Clock::time_point deadline = start + std::chrono::milliseconds(options_.deadlineMs);
  Status status;
  int tries = 0;
  for (int attempt = 0; attempt <= options_.retries; ++attempt) {
    const long left = long(std::chrono::duration_cast<std::chrono::milliseconds>(deadline - Clock::now()).count());
    if (left <= 0) break;
    bool permanent = false, remember = false;
    ++tries;
    status = tryRead(data, bytes, offset, std::min(options_.timeoutMs, left), permanent, remember, totalSize);
    if (status) return status;
    if (permanent) {
      if (remember) rememberFailure(status.error());
      return status;
    }
    if (attempt < options_.retries) {
      const long pause = options_.backoffMs << std::min(attempt, 20);
      if (Clock::now() + std::chrono::milliseconds(pause) >= deadline) break;
      ++retries_;
      std::this_thread::sleep_for(std::chrono::milliseconds(pause));
    }
  }
  const double seconds = std::chrono::duration<double>(Clock::now() - start).count();
  const Error error = makeError("{} (after {} {} in {:.1f} s)", status.error().message, tries,
                                tries == 1 ? "try" : "tries", seconds);
  rememberFailure(error);
  return error;
}

void HttpByteSource::rememberFailure(const Error& error) const {
  if (options_.coolDownMs <= 0) return;
  FailedUrls& urls = failedUrls();
  std::lock_guard lock(urls.mutex);
  urls.failures[url_] = {Clock::now() + std::chrono::milliseconds(options_.coolDownMs), error.message};
}

}  // namespace tellus
