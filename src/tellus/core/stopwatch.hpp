#pragma once
// Wall-clock time of a stage, in milliseconds, on the monotonic clock: the one way the
// libraries time what they report (a stage's cost in a report, a time budget).
#include <chrono>

namespace tellus {

class Stopwatch {
 public:
  using Clock = std::chrono::steady_clock;

  Stopwatch() : start_(Clock::now()) {}
  // Milliseconds since construction or the last restart()/lapMs().
  double elapsedMs() const { return std::chrono::duration<double, std::milli>(Clock::now() - start_).count(); }
  // Seconds, likewise.
  double elapsedS() const { return elapsedMs() / 1000.0; }
  void restart() { start_ = Clock::now(); }
  // elapsedMs(), then restart(): the time of one stage of several in a row.
  double lapMs() {
    const Clock::time_point now = Clock::now();
    const double ms = std::chrono::duration<double, std::milli>(now - start_).count();
    start_ = now;
    return ms;
  }

 private:
  Clock::time_point start_;
};

}  // namespace tellus
