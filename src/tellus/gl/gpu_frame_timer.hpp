#pragma once
// GPU time of frames from GL_TIME_ELAPSED queries, read back without stalling the pipeline:
// each frame uses the next query of a ring; results are collected once the GPU has them
// (poll()), and only finish() waits. A frame whose query is still in flight when the ring wraps
// is waited for (the ring is sized so that this does not happen at normal latencies).
// Needs a current GL 4.5 context.
#include <cstdint>
#include <optional>
#include <vector>

#include "tellus/gl/query.hpp"

namespace tellus::gl {

class GpuFrameTimer {
 public:
  explicit GpuFrameTimer(int framesInFlight = 8);

  // Brackets the GL commands of frame `frame` (any caller-chosen index).
  void beginFrame(std::uint64_t frame);
  void endFrame();

  struct Sample {
    std::uint64_t frame = 0;
    double milliseconds = 0.0;
  };
  // Results that became available since the last call, in frame order. Never stalls.
  std::vector<Sample> poll();
  // Waits for every frame still in flight and returns their results.
  std::vector<Sample> finish();

 private:
  struct Slot {
    Query query;
    std::optional<std::uint64_t> frame;  // set while in flight
  };
  std::vector<Sample> collect(bool wait);

  std::vector<Slot> slots_;
  std::size_t next_ = 0;
  std::vector<Sample> pending_;  // collected while a full ring was forced
};

}  // namespace tellus::gl
