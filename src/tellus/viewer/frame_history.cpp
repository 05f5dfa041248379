#include "tellus/viewer/frame_history.hpp"

#include <algorithm>

namespace tellus {
namespace {

double medianOf(std::vector<float> values) {
  if (values.empty()) return -1.0;
  const auto middle = values.begin() + std::ptrdiff_t(values.size() / 2);
  std::nth_element(values.begin(), middle, values.end());
  return *middle;
}

std::vector<float> knownValues(const std::vector<float>& values) {
  std::vector<float> known;
  std::copy_if(values.begin(), values.end(), std::back_inserter(known),
               [](float v) { return v >= 0.0f; });
  return known;
}

}  // namespace

FrameHistory::FrameHistory(std::size_t capacity) : capacity_(std::max<std::size_t>(1, capacity)) {}

void FrameHistory::add(double cpuMs, double gpuMs, double intervalMs) {
  if (cpuMs_.size() < capacity_) {
    cpuMs_.push_back(float(cpuMs));
    gpuMs_.push_back(float(gpuMs));
    intervalMs_.push_back(float(intervalMs));
    return;
  }
  cpuMs_[next_] = float(cpuMs);
  gpuMs_[next_] = float(gpuMs);
  intervalMs_[next_] = float(intervalMs);
  next_ = (next_ + 1) % capacity_;
}

void FrameHistory::setGpuMs(std::size_t framesAgo, double gpuMs) {
  if (framesAgo >= gpuMs_.size()) return;
  // The last frame sits just before next_ once the ring is full, at the end before that.
  const std::size_t last =
      cpuMs_.size() < capacity_ ? cpuMs_.size() - 1 : (next_ + capacity_ - 1) % capacity_;
  gpuMs_[(last + capacity_ - framesAgo) % capacity_] = float(gpuMs);
}

std::vector<float> FrameHistory::series(const std::vector<float>& ring) const {
  if (ring.size() < capacity_) return ring;
  std::vector<float> ordered(ring.begin() + std::ptrdiff_t(next_), ring.end());
  ordered.insert(ordered.end(), ring.begin(), ring.begin() + std::ptrdiff_t(next_));
  return ordered;
}

double FrameHistory::medianCpuMs() const {
  return medianOf(cpuMs_);
}

double FrameHistory::medianGpuMs() const {
  return medianOf(knownValues(gpuMs_));
}

double FrameHistory::medianIntervalMs() const {
  return medianOf(knownValues(intervalMs_));
}

}  // namespace tellus
