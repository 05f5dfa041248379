#include "tellus/core/progress.hpp"

#include <unistd.h>

#include <cstdio>

namespace tellus {
namespace {
std::atomic<bool> gEnabled{true};
}

void Progress::setEnabled(bool enabled) {
  gEnabled = enabled;
}

Progress::Progress(std::string label, std::uint64_t total)
    : label_(std::move(label)), total_(total), active_(gEnabled && ::isatty(STDERR_FILENO) == 1) {}

Progress::~Progress() {
  if (active_) std::fprintf(stderr, "\r\033[2K");
}

void Progress::advance(std::uint64_t steps) {
  const std::uint64_t done = done_.fetch_add(steps) + steps;
  if (active_) draw(done);
}

void Progress::set(std::uint64_t done) {
  done_ = done;
  if (active_) draw(done);
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

}  // namespace tellus
