#pragma once
// Deterministic camera paths over a terrain, the same for every renderer compared on them.
//
//   orbit    a full circle around the terrain's centre, looking at it 25-35 degrees down;
//   flyover  low altitude along the south-west to north-east diagonal, across the whole
//            terrain, clearing the ground below and ahead, looking forward and down;
//   walk     eye height (2 m) above the ground, following it, through the centre from west to
//            east over 2 km (at most a fifth of the terrain's width), looking ahead;
//   rotate   seed 004's camera test: a fixed position above the terrain's centre, a little
//            above the highest ground around it, turning through 360 one-degree steps
//            (yaw 0..359, sample the path at 360 frames to get exactly those), 8 degrees down;
//   FILE.json keyframes {"keyframes": [{"time": s, "position": [x, y, z], "yaw": deg,
//            "pitch": deg, "fov": deg}, ...]} interpolated smoothly (Catmull-Rom through the
//            keyframes; yaw along the shorter way round).
//
// A path is sampled at N frames evenly spaced in time, first and last keyframe included.
// World frame and camera conventions: camera.hpp. GL-free.
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "tellus/core/camera.hpp"
#include "tellus/core/result.hpp"
#include "tellus/dem/height_grid.hpp"

namespace tellus {

struct CameraKeyframe {
  double timeS = 0.0;
  Camera camera;
};

// Limits on keyframe paths (they come from files users edit).
inline constexpr std::size_t kMaxKeyframes = 1'000'000;
inline constexpr double kMaxKeyframeTimeS = 1e9;
inline constexpr std::size_t kMaxCameraPathBytes = std::size_t(256) << 20;

class CameraPath {
 public:
  // Keyframes must be at least two (at most kMaxKeyframes), with strictly increasing times
  // within +-kMaxKeyframeTimeS and cameras that pass checkCamera().
  static Result<CameraPath> fromKeyframes(std::vector<CameraKeyframe> keyframes);

  const std::vector<CameraKeyframe>& keyframes() const { return keyframes_; }
  double durationS() const { return keyframes_.back().timeS - keyframes_.front().timeS; }
  // The camera at time t (clamped to the path's time range).
  Camera at(double timeS) const;
  // `frames` cameras evenly spaced in time; frames >= 1 (1 gives the first keyframe).
  std::vector<Camera> sample(int frames) const;

 private:
  std::vector<CameraKeyframe> keyframes_;
};

// "orbit", "flyover", "walk", "rotate" or a path to a keyframe JSON file.
Result<CameraPath> makeCameraPath(std::string_view nameOrFile, const HeightGrid& terrain);
std::vector<std::string_view> builtInPathNames();

// Reads a keyframe JSON file (a regular file of at most kMaxCameraPathBytes).
Result<CameraPath> loadCameraPath(const std::filesystem::path& file);
// Parses keyframe JSON text; `name` is for messages.
Result<CameraPath> parseCameraPath(std::string_view text, const std::string& name);
// Writes the keyframe JSON (atomically) that loadCameraPath() reads.
Status saveCameraPath(const CameraPath& path, const std::filesystem::path& file);

// Highest point, over the candidate surfaces a renderer may draw for the cell under (x, y)
// (bilinear and both diagonal triangulations), metres. A camera above it is above the mesh.
double groundUpperBound(const HeightGrid& terrain, double x, double y);

}  // namespace tellus
