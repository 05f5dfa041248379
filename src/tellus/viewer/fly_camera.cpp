#include "tellus/viewer/fly_camera.hpp"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>

namespace tellus {

double FlyCameraController::speedMps(double heightAboveGroundM) const {
  return std::max(kMinSpeedMps, heightAboveGroundM) * speedFactor_;
}

void FlyCameraController::setSpeedFactor(double factor) {
  speedFactor_ = std::clamp(factor, 1e-3, 1e3);
}

void FlyCameraController::scroll(double steps) {
  setSpeedFactor(speedFactor_ * std::pow(kScrollFactor, steps));
}

void FlyCameraController::update(Camera& camera, const FlyInput& input, double dtS,
                                 const std::function<double(double, double)>& groundAt) {
  scroll(input.scrollSteps);
  applyInput(camera, input, dtS, groundAt(camera.position.x, camera.position.y));
  clampAboveGround(camera, groundAt(camera.position.x, camera.position.y));
}

void FlyCameraController::applyInput(Camera& camera, const FlyInput& input, double dtS,
                                     double groundM) const {
  camera.yawDeg = std::fmod(camera.yawDeg + input.mouseDeltaPx.x * kLookDegPerPx + 360.0, 360.0);
  camera.pitchDeg = std::clamp(camera.pitchDeg - input.mouseDeltaPx.y * kLookDegPerPx, -89.0, 89.0);

  glm::dvec3 direction{0.0};
  if (input.forward) direction += camera.forward();
  if (input.back) direction -= camera.forward();
  if (input.right) direction += camera.right();
  if (input.left) direction -= camera.right();
  if (input.up) direction.z += 1.0;
  if (input.down) direction.z -= 1.0;
  const double length = glm::length(direction);
  if (length == 0.0) return;
  const double speed = speedMps(camera.position.z - groundM) * (input.fast ? kFastFactor : 1.0);
  camera.position += direction / length * (speed * dtS);
}

void FlyCameraController::dropToWalkingHeight(Camera& camera, double groundM) {
  camera.position.z = groundM + kWalkEyeHeightM;
  camera.pitchDeg = 0.0;
}

void FlyCameraController::clampAboveGround(Camera& camera, double groundM) {
  camera.position.z = std::max(camera.position.z, groundM + kMinClearanceM);
}

Camera FlyCameraController::frameAll(const Aabb& bounds, double aspect, double fovYDeg,
                                     double yawDeg) {
  return overviewCamera(bounds, aspect, fovYDeg, -45.0, yawDeg);
}

}  // namespace tellus
