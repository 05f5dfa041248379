#pragma once
// Progress of long-running work. On a terminal, a one-line indicator redrawn at most ~10 times
// a second; otherwise (logs, CI, a pipe) one plain line every 10 seconds of work (the
// environment variable TELLUS_PROGRESS_LOG_SECONDS sets another interval) with the fraction
// done, the elapsed time and an estimate of what is left, so that a long run is never silent
// in a log and short runs print nothing. The lines come from a heartbeat thread too, so a
// step that takes minutes (one GDAL warp) does not silence the log. Thread-safe: advance()
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
  // True when the terminal line is drawn (stderr is a terminal and progress is enabled).
  // Callers may use it to skip work that only serves the display.
  bool active() const { return active_; }

  // Globally disables drawing and logging (e.g. --quiet).
  static void setEnabled(bool enabled);

 private:
  void draw(std::uint64_t done);
  void log(std::uint64_t done);

  std::string label_;
  std::uint64_t total_;
  std::atomic<std::uint64_t> done_{0};
  bool active_;   // a terminal: the redrawn line
  bool logging_;  // not a terminal: a line now and then
  std::chrono::steady_clock::duration logInterval_;
  std::mutex drawMutex_;
  std::chrono::steady_clock::time_point start_, lastDraw_{};
  std::atomic<std::chrono::steady_clock::rep> lastLog_;  // ticks since the epoch
};

}  // namespace tellus
