#include "tellus/gl/gpu_frame_timer.hpp"

#include <algorithm>

namespace tellus::gl {

GpuFrameTimer::GpuFrameTimer(int framesInFlight) {
  for (int i = 0; i < std::max(2, framesInFlight); ++i) {
    slots_.push_back({Query::create(GL_TIME_ELAPSED), std::nullopt});
  }
}

void GpuFrameTimer::beginFrame(std::uint64_t frame) {
  Slot& slot = slots_[next_];
  if (slot.frame) {  // the ring wrapped onto a frame still in flight: wait for it
    pending_.push_back({*slot.frame, double(slot.query.result()) * 1e-6});
    slot.frame.reset();
  }
  slot.frame = frame;
  slot.query.begin();
}

void GpuFrameTimer::endFrame() {
  slots_[next_].query.end();
  next_ = (next_ + 1) % slots_.size();
}

std::vector<GpuFrameTimer::Sample> GpuFrameTimer::collect(bool wait) {
  std::vector<Sample> samples;
  samples.swap(pending_);
  // Oldest first: the slots after next_ were started earliest.
  for (std::size_t k = 0; k < slots_.size(); ++k) {
    Slot& slot = slots_[(next_ + k) % slots_.size()];
    if (!slot.frame) continue;
    if (!wait && !slot.query.available()) continue;
    samples.push_back({*slot.frame, double(slot.query.result()) * 1e-6});
    slot.frame.reset();
  }
  std::sort(samples.begin(), samples.end(),
            [](const Sample& a, const Sample& b) { return a.frame < b.frame; });
  return samples;
}

std::vector<GpuFrameTimer::Sample> GpuFrameTimer::poll() {
  return collect(false);
}
std::vector<GpuFrameTimer::Sample> GpuFrameTimer::finish() {
  return collect(true);
}

}  // namespace tellus::gl
