#pragma once
// Records the camera as the user flies into keyframes of a camera path: a CameraPath on a flat
// world, which saveCameraPath() writes as the keyframe JSON that `tellus bench --path FILE.json`
// and `tellus view --path FILE.json` replay, or a GeoCameraPath on the globe, which
// saveGeoCameraPath() writes as lat/lon keyframes for the same commands. GL-free.
//
// A keyframe is kept when at least `intervalS` has passed since the previous one (the path
// interpolates smoothly between keyframes); finish() always keeps the last camera seen, so the
// path ends where the recording stopped.
#include <optional>
#include <utility>
#include <vector>

#include "tellus/core/result.hpp"
#include "tellus/eval/camera_path.hpp"
#include "tellus/eval/geo_camera_path.hpp"

namespace tellus {

// Keyframe: {double timeS; CameraT camera;}; Path::fromKeyframes(std::vector<Keyframe>).
template <typename CameraT, typename Keyframe, typename Path>
class KeyframeRecorder {
 public:
  explicit KeyframeRecorder(double intervalS = 0.25) : intervalS_(intervalS) {}

  bool recording() const { return recording_; }
  // Starts a new recording (discarding any earlier one); times are relative to `timeS`.
  void start(double timeS) {
    recording_ = true;
    startS_ = timeS;
    keyframes_.clear();
    latest_.reset();
  }
  // The camera at `timeS` (non-decreasing between calls). Ignored when not recording.
  void add(double timeS, const CameraT& camera) {
    if (!recording_) return;
    const Keyframe keyframe{timeS - startS_, camera};
    latest_ = keyframe;
    // (With a tolerance, so that frame times that are multiples of the interval land on it.)
    if (keyframes_.empty() || keyframe.timeS - keyframes_.back().timeS >= intervalS_ - 1e-9) {
      keyframes_.push_back(keyframe);
    }
  }
  // Stops and returns the recorded path. Error when fewer than two distinct times were seen
  // (a path needs a beginning and an end).
  Result<Path> finish() {
    recording_ = false;
    if (latest_ && !keyframes_.empty() && latest_->timeS > keyframes_.back().timeS) {
      keyframes_.push_back(*latest_);
    }
    latest_.reset();
    std::vector<Keyframe> keyframes = std::move(keyframes_);
    keyframes_.clear();
    if (keyframes.size() < 2) {
      return makeError("the recording is too short: a path needs cameras at two different times");
    }
    return Path::fromKeyframes(std::move(keyframes));
  }
  std::size_t keyframeCount() const { return keyframes_.size(); }

 private:
  double intervalS_;
  bool recording_ = false;
  double startS_ = 0.0;
  std::vector<Keyframe> keyframes_;
  std::optional<Keyframe> latest_;  // last camera seen, kept at finish()
};

using PathRecorder = KeyframeRecorder<Camera, CameraKeyframe, CameraPath>;
using GeoPathRecorder = KeyframeRecorder<GeoCamera, GeoCameraKeyframe, GeoCameraPath>;

}  // namespace tellus
