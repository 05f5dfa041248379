#include "tellus/viewer/path_recorder.hpp"

namespace tellus {

void PathRecorder::start(double timeS) {
  recording_ = true;
  startS_ = timeS;
  keyframes_.clear();
  latest_.reset();
}

void PathRecorder::add(double timeS, const Camera& camera) {
  if (!recording_) return;
  const CameraKeyframe keyframe{timeS - startS_, camera};
  latest_ = keyframe;
  // (With a tolerance, so that frame times that are multiples of the interval land on it.)
  if (keyframes_.empty() || keyframe.timeS - keyframes_.back().timeS >= intervalS_ - 1e-9) {
    keyframes_.push_back(keyframe);
  }
}

Result<CameraPath> PathRecorder::finish() {
  recording_ = false;
  if (latest_ && !keyframes_.empty() && latest_->timeS > keyframes_.back().timeS) {
    keyframes_.push_back(*latest_);
  }
  latest_.reset();
  std::vector<CameraKeyframe> keyframes = std::move(keyframes_);
  keyframes_.clear();
  if (keyframes.size() < 2) {
    return makeError("the recording is too short: a path needs cameras at two different times");
  }
  return CameraPath::fromKeyframes(std::move(keyframes));
}

}  // namespace tellus
