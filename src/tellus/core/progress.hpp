#pragma once
// A one-line progress indicator for long-running work. It draws only when stderr is a
// terminal (so logs and CI stay quiet), at most ~10 times a second. Thread-safe: advance()
// may be called from worker threads.
#include <atomic>
#include <chrono>
#include <cstdint>
#include <mutex>
#include <string>

namespace tellus {

class Progress {
 public:
  Progress(std::string label, std::uint64_t total);
  ~Progress();  // clears the line
  Progress(const Progress&) = delete;
  Progress& operator=(const Progress&) = delete;

  void advance(std::uint64_t steps = 1);
  // Sets the amount done so far (for callbacks that report a fraction).
  void set(std::uint64_t done);
  // True when the line is drawn (stderr is a terminal and progress is enabled). Callers may use
  // it to skip work that only serves the display.
  bool active() const { return active_; }

  // Globally disables drawing (e.g. --quiet).
  static void setEnabled(bool enabled);

 private:
  void draw(std::uint64_t done);

  std::string label_;
  std::uint64_t total_;
  std::atomic<std::uint64_t> done_{0};
  bool active_;
  std::mutex drawMutex_;
  std::chrono::steady_clock::time_point lastDraw_{};
};

}  // namespace tellus
