#pragma once
// The viewer's fly-through camera, free of GLFW and GL so that it can be tested: the window
// turns keys, mouse and scroll wheel into a FlyInput, and update() moves the Camera.
//
// - Mouse look: yaw and pitch follow the mouse (degrees per pixel), pitch within +-89 degrees.
// - WASD move along the view direction (forward/back) and sideways, Q/E straight down/up.
//   The speed is the height above the ground per second (so one covers the view's scale in a
//   second at any altitude), at least kMinSpeedMps, times the user's speed factor; Shift
//   multiplies it by 4.
// - The scroll wheel changes the speed factor by 25% per step.
// - The camera never goes below the ground plus kMinClearanceM.
// World frame and camera conventions: camera.hpp.
#include <functional>

#include <glm/vec2.hpp>

#include "tellus/core/aabb.hpp"
#include "tellus/core/camera.hpp"

namespace tellus {

struct FlyInput {
  bool forward = false, back = false, left = false, right = false;
  bool down = false, up = false;
  bool fast = false;                  // Shift held
  glm::dvec2 mouseDeltaPx{0.0, 0.0};  // mouse movement while looking (x right, y down)
  double scrollSteps = 0.0;           // wheel steps, positive away from the user
};

class FlyCameraController {
 public:
  static constexpr double kMinSpeedMps = 2.0;
  static constexpr double kMinClearanceM = 0.5;
  static constexpr double kWalkEyeHeightM = 2.0;  // as the built-in "walk" path
  static constexpr double kLookDegPerPx = 0.15;
  static constexpr double kFastFactor = 4.0;
  static constexpr double kScrollFactor = 1.25;

  // One frame: the scroll steps change the speed factor, then `camera` looks and moves by
  // `input` over `dtS` seconds and is kept above the ground. groundAt(x, y): terrain height in
  // metres at world (x, y) (e.g. groundUpperBound of the height grid).
  void update(Camera& camera, const FlyInput& input, double dtS,
              const std::function<double(double, double)>& groundAt);

  // Metres per second at `heightAboveGroundM` with the current speed factor (without Shift).
  double speedMps(double heightAboveGroundM) const;
  double speedFactor() const { return speedFactor_; }
  void setSpeedFactor(double factor);

  // Looks (yaw, pitch) and moves (position) as `input` says; no ground clamping.
  void applyInput(Camera& camera, const FlyInput& input, double dtS, double groundM) const;
  void scroll(double steps);

  // Drops the camera to eye height above `groundM`, looking level.
  static void dropToWalkingHeight(Camera& camera, double groundM);
  // Raises the camera to at least `groundM` + kMinClearanceM.
  static void clampAboveGround(Camera& camera, double groundM);
  // The whole terrain `bounds` in view, looking `yawDeg` (the current heading) 45 degrees down.
  static Camera frameAll(const Aabb& bounds, double aspect, double fovYDeg, double yawDeg);

 private:
  double speedFactor_ = 1.0;
};

}  // namespace tellus
