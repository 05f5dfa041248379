#pragma once
// The last N frames' timings, for the viewer's frame-time graph and its running medians.
// GL-free.
#include <cstddef>
#include <vector>

namespace tellus {

class FrameHistory {
 public:
  explicit FrameHistory(std::size_t capacity = 240);

  // One frame: CPU milliseconds (LOD selection + submission), GPU milliseconds (negative
  // when the GPU time of this frame is not known yet) and the wall-clock time since the
  // previous frame began (negative for the first), which is what the user sees.
  void add(double cpuMs, double gpuMs, double intervalMs = -1.0);
  // Sets the GPU time of the frame added `framesAgo` frames ago (0 = the last one): GPU timer
  // results arrive a few frames late. Ignored when that frame has left the history.
  void setGpuMs(std::size_t framesAgo, double gpuMs);

  std::size_t size() const { return cpuMs_.size(); }
  // Oldest first, for plotting.
  std::vector<float> cpuSeries() const { return series(cpuMs_); }
  std::vector<float> gpuSeries() const { return series(gpuMs_); }
  // Medians over the history; the GPU one over known values only (-1 when none).
  double medianCpuMs() const;
  double medianGpuMs() const;
  double medianIntervalMs() const;  // -1 when none is known

 private:
  std::vector<float> series(const std::vector<float>& ring) const;
  std::size_t capacity_;
  std::size_t next_ = 0;  // where the next frame goes once the ring is full
  std::vector<float> cpuMs_, gpuMs_, intervalMs_;
};

}  // namespace tellus
