#include "tellus/core/progress.hpp"

#include <unistd.h>

#include <algorithm>
#include <condition_variable>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <map>
#include <mutex>
#include <string>
#include <thread>

namespace tellus {
namespace {
std::atomic<bool> gEnabled{true};

std::chrono::steady_clock::duration logIntervalFromEnvironment() {
  double seconds = 10.0;
  if (const char* text = std::getenv("TELLUS_PROGRESS_LOG_SECONDS"); text && *text) {
    char* end = nullptr;
    const double value = std::strtod(text, &end);
    if (*end == '\0' && value >= 0.1 && value <= 3600.0) seconds = value;
  }
  return std::chrono::duration_cast<std::chrono::steady_clock::duration>(
      std::chrono::duration<double>(seconds));
}

// "42 s", "3 min 5 s", "2 h 10 min".
std::string formatSeconds(double seconds) {
  const long s = long(seconds + 0.5);
  if (s < 60) return std::to_string(s) + " s";
  if (s < 3600) return std::to_string(s / 60) + " min " + std::to_string(s % 60) + " s";
  return std::to_string(s / 3600) + " h " + std::to_string((s % 3600) / 60) + " min";
}
// Logs every live Progress of this process at its interval, also while its work makes no
// step (one GDAL warp of a huge source can take minutes): a log is never silent for long.
class Heartbeat {
 public:
  static Heartbeat& instance() {
    static Heartbeat heartbeat;
    return heartbeat;
  }
  void add(Progress* progress, const std::function<void()>& beat) {
    std::lock_guard lock(mutex_);
    beats_[progress] = beat;
    if (!thread_.joinable()) thread_ = std::thread([this] { run(); });
  }
  void remove(Progress* progress) {
    std::lock_guard lock(mutex_);
    beats_.erase(progress);
  }
  ~Heartbeat() {
    {
      std::lock_guard lock(mutex_);
      stop_ = true;
    }
    wake_.notify_all();
    if (thread_.joinable()) thread_.join();
  }

 private:
  void run() {
    std::unique_lock lock(mutex_);
    while (!stop_) {
      wake_.wait_for(lock, std::chrono::milliseconds(100));
      for (auto& [progress, beat] : beats_) beat();  // under the lock: none is destroyed meanwhile
    }
  }
  std::mutex mutex_;
  std::condition_variable wake_;
  std::map<Progress*, std::function<void()>> beats_;
  bool stop_ = false;
  std::thread thread_;
};
}  // namespace

void Progress::setEnabled(bool enabled) {
  gEnabled = enabled;
}

Progress::Progress(std::string label, std::uint64_t total)
    : label_(std::move(label)),
      total_(total),
      active_(gEnabled && ::isatty(STDERR_FILENO) == 1),
      logging_(gEnabled && !active_),
      logInterval_(logIntervalFromEnvironment()),
      start_(std::chrono::steady_clock::now()),
      lastDraw_(start_),
      lastLog_(start_.time_since_epoch().count()) {
  if (logging_) Heartbeat::instance().add(this, [this] { log(done_.load()); });
}

Progress::~Progress() {
  if (logging_) Heartbeat::instance().remove(this);
  if (active_) std::fprintf(stderr, "\r\033[2K");
}

void Progress::advance(std::uint64_t steps) {
  const std::uint64_t done = done_.fetch_add(steps) + steps;
  if (active_) draw(done);
  if (logging_) log(done);
}

void Progress::set(std::uint64_t done) {
  done_ = done;
  if (active_) draw(done);
  if (logging_) log(done);
}

void Progress::draw(std::uint64_t done) {
  std::unique_lock lock(drawMutex_, std::try_to_lock);
  if (!lock) return;
  const auto now = std::chrono::steady_clock::now();
  if (done < total_ && now - lastDraw_ < std::chrono::milliseconds(100)) return;
  lastDraw_ = now;
  const double fraction = total_ ? double(done) / double(total_) : 1.0;
  std::fprintf(stderr, "\r\033[2K%s %3.0f%%", label_.c_str(), fraction * 100.0);
  std::fflush(stderr);
}

void Progress::log(std::uint64_t done) {
  const auto now = std::chrono::steady_clock::now();
  auto last = lastLog_.load(std::memory_order_relaxed);
  // One thread wins the interval's line; the others return at once.
  if (now.time_since_epoch().count() - last < logInterval_.count() ||
      !lastLog_.compare_exchange_strong(last, now.time_since_epoch().count())) {
    return;
  }
  const double fraction = total_ ? double(std::min(done, total_)) / double(total_) : 1.0;
  const double elapsed = std::chrono::duration<double>(now - start_).count();
  // An estimate from under 1 % of the work says more about start-up than about the rest.
  std::string left = "not known yet";
  if (fraction >= 0.01) left = "about " + formatSeconds(elapsed * (1.0 - fraction) / fraction);
  std::fprintf(stderr, "tellus: %s: %.1f%% (%llu of %llu), %s elapsed, %s left\n", label_.c_str(),
               fraction * 100.0, static_cast<unsigned long long>(done),
               static_cast<unsigned long long>(total_), formatSeconds(elapsed).c_str(),
               left.c_str());
  std::fflush(stderr);
}

}  // namespace tellus
