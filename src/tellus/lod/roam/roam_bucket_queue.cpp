#include "tellus/lod/roam/roam_bucket_queue.hpp"

#include <algorithm>
#include <cmath>

namespace tellus::roam {

int BucketQueue::bucketOf(float priority) {
  if (!(priority > kMinPriority)) return 0;  // also NaN
  const float octaves = std::log2(priority / kMinPriority);
  return std::min(kBuckets - 1, 1 + int(octaves * float(kBucketsPerOctave)));
}

void BucketQueue::grow(std::int32_t id) {
  const std::size_t need = std::size_t(id) + 1;
  if (need <= bucket_.size()) return;
  const std::size_t size = std::max(need, bucket_.size() * 2);
  next_.resize(size, -1);
  prev_.resize(size, -1);
  bucket_.resize(size, -1);
  priority_.resize(size, 0.0f);
}

void BucketQueue::link(std::int32_t id, int bucket) {
  const auto i = std::size_t(id);
  bucket_[i] = bucket;
  prev_[i] = -1;
  next_[i] = head_[std::size_t(bucket)];
  if (next_[i] >= 0) prev_[std::size_t(next_[i])] = id;
  head_[std::size_t(bucket)] = id;
  highest_ = std::max(highest_, bucket);
  lowest_ = std::min(lowest_, bucket);
}

void BucketQueue::unlink(std::int32_t id) {
  const auto i = std::size_t(id);
  if (prev_[i] >= 0) {
    next_[std::size_t(prev_[i])] = next_[i];
  } else {
    head_[std::size_t(bucket_[i])] = next_[i];
  }
  if (next_[i] >= 0) prev_[std::size_t(next_[i])] = prev_[i];
  bucket_[i] = -1;
}

void BucketQueue::set(std::int32_t id, float priority) {
  grow(id);
  const int bucket = bucketOf(priority);
  priority_[std::size_t(id)] = priority;
  const int old = bucket_[std::size_t(id)];
  if (old == bucket) return;
  if (old >= 0) {
    unlink(id);
  } else {
    ++size_;
  }
  link(id, bucket);
}

void BucketQueue::remove(std::int32_t id) {
  if (!contains(id)) return;
  unlink(id);
  --size_;
}

std::int32_t BucketQueue::top() {
  if (size_ == 0) return -1;
  while (highest_ >= 0 && head_[std::size_t(highest_)] < 0) --highest_;
  return highest_ >= 0 ? head_[std::size_t(highest_)] : -1;
}

std::int32_t BucketQueue::bottom() {
  if (size_ == 0) return -1;
  while (lowest_ < kBuckets && head_[std::size_t(lowest_)] < 0) ++lowest_;
  return lowest_ < kBuckets ? head_[std::size_t(lowest_)] : -1;
}

}  // namespace tellus::roam
