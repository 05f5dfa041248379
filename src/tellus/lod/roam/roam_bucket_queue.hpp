#pragma once
// ROAM's priority queues (Duchaineau et al. 1997, section 6): elements (small integer ids) kept
// in buckets by a monotonic quantisation of their priority, so insert, remove and re-prioritise
// are O(1) and the highest or lowest bucket is found by a scan from a cached bound. Elements of
// one bucket are in no particular order; the queue's top is exact to within a bucket (the seed
// accepts this; decisions against the error target compare exact priorities).
//
// Priorities are screen-space errors in pixels, >= 0; buckets are spaced logarithmically
// (kBucketsPerOctave per doubling) from kMinPriority up, everything below in bucket 0.
#include <cstdint>
#include <vector>

namespace tellus::roam {

class BucketQueue {
 public:
  static constexpr int kBuckets = 1024;
  static constexpr int kBucketsPerOctave = 32;
  static constexpr float kMinPriority = 1.0f / 1024.0f;  // pixels; bucket 0 holds all below

  static int bucketOf(float priority);

  bool contains(std::int32_t id) const {
    return id >= 0 && std::size_t(id) < bucket_.size() && bucket_[std::size_t(id)] >= 0;
  }
  bool empty() const { return size_ == 0; }
  std::size_t size() const { return size_; }
  float priority(std::int32_t id) const { return priority_[std::size_t(id)]; }

  // Adds `id` (not queued yet) or moves it to the bucket of `priority` (queued).
  void set(std::int32_t id, float priority);
  void remove(std::int32_t id);  // no-op when not queued
  // An element of the highest / lowest non-empty bucket; -1 when empty.
  std::int32_t top();
  std::int32_t bottom();

 private:
  void grow(std::int32_t id);
  void link(std::int32_t id, int bucket);
  void unlink(std::int32_t id);

  std::vector<std::int32_t> head_ = std::vector<std::int32_t>(kBuckets, -1);
  std::vector<std::int32_t> next_, prev_;
  std::vector<std::int32_t> bucket_;  // -1: not queued
  std::vector<float> priority_;
  std::size_t size_ = 0;
  int highest_ = -1;       // no non-empty bucket above it
  int lowest_ = kBuckets;  // no non-empty bucket below it
};

}  // namespace tellus::roam
