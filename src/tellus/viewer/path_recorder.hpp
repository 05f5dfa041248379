#pragma once
// Records the camera as the user flies into keyframes for a CameraPath, which
// saveCameraPath() writes as the keyframe JSON that `tellus bench --path FILE.json` and
// `tellus view --path FILE.json` replay. GL-free.
//
// A keyframe is kept when at least `intervalS` has passed since the previous one (the path
// interpolates smoothly between keyframes); finish() always keeps the last camera seen, so the
// path ends where the recording stopped.
#include <optional>
#include <vector>

#include "tellus/core/result.hpp"
#include "tellus/eval/camera_path.hpp"

namespace tellus {

class PathRecorder {
 public:
  explicit PathRecorder(double intervalS = 0.25) : intervalS_(intervalS) {}

  bool recording() const { return recording_; }
  // Starts a new recording (discarding any earlier one); times are relative to `timeS`.
  void start(double timeS);
  // The camera at `timeS` (non-decreasing between calls). Ignored when not recording.
  void add(double timeS, const Camera& camera);
  // Stops and returns the recorded path. Error when fewer than two distinct times were seen
  // (a path needs a beginning and an end).
  Result<CameraPath> finish();
  std::size_t keyframeCount() const { return keyframes_.size(); }

 private:
  double intervalS_;
  bool recording_ = false;
  double startS_ = 0.0;
  std::vector<CameraKeyframe> keyframes_;
  std::optional<CameraKeyframe> latest_;  // last camera seen, kept at finish()
};

}  // namespace tellus
