#include "tellus/viewer/globe_camera.hpp"

#include <algorithm>
#include <cmath>

#include "tellus/core/geodesy.hpp"

namespace tellus {
namespace {

constexpr double kMetresPerDegree = 111'320.0;

double wrap180(double degrees) {
  double d = std::fmod(degrees + 180.0, 360.0);
  if (d < 0.0) d += 360.0;
  return d - 180.0;
}

// Moves the camera over the ground by `east`, `north` metres (a local approximation: the steps
// are a frame's worth of motion).
void moveOverGround(GeoCamera& c, double eastM, double northM) {
  c.latDeg = std::clamp(c.latDeg + northM / kMetresPerDegree, -89.9, 89.9);
  const double perLonDegree = kMetresPerDegree * std::max(std::cos(c.latDeg * wgs84::kDegree), 1e-3);
  c.lonDeg = wrap180(c.lonDeg + eastM / perLonDegree);
}

}  // namespace

double GlobeCameraController::flyWeight(double clearanceM) {
  const double t = (std::log(kOrbitAboveM) - std::log(std::max(clearanceM, 1e-3))) /
                   (std::log(kOrbitAboveM) - std::log(kFlyBelowM));
  const double x = std::clamp(t, 0.0, 1.0);
  return x * x * (3.0 - 2.0 * x);
}

void GlobeCameraController::setFlyPitchDeg(double pitchDeg) {
  flyPitchDeg_ = std::clamp(pitchDeg, -89.0, 89.0);
}

void GlobeCameraController::update(GeoCamera& c, const GlobeInput& in, double dtS,
                                   int viewHeightPx, const GlobeGroundFn& groundAt) {
  double ground = groundAt(c.latDeg, c.lonDeg);
  if (!std::isfinite(ground)) ground = 0.0;
  double clearance = std::max(c.altitudeM - ground, kMinClearanceM);
  const double fly = flyWeight(clearance);
  const double heading = c.headingDeg * wgs84::kDegree;
  // Drag: turn the globe (the ground follows the cursor) and/or look around.
  if (in.dragPx.x != 0.0 || in.dragPx.y != 0.0) {
    const double metresPerPx =
        2.0 * clearance * std::tan(0.5 * c.fovYDeg * wgs84::kDegree) / std::max(viewHeightPx, 1);
    const double rightM = -in.dragPx.x * metresPerPx * (1.0 - fly);
    const double forwardM = in.dragPx.y * metresPerPx * (1.0 - fly);
    moveOverGround(c, rightM * std::cos(heading) + forwardM * std::sin(heading),
                   -rightM * std::sin(heading) + forwardM * std::cos(heading));
    c.headingDeg = wrap180(c.headingDeg + in.dragPx.x * kLookDegPerPx * fly);
    setFlyPitchDeg(flyPitchDeg_ - in.dragPx.y * kLookDegPerPx * fly);
  }
  // Wheel: the clearance changes geometrically; the camera moves towards (or away from) the
  // point under the cursor by the same fraction, so that point stays under the cursor.
  if (in.scrollSteps != 0.0) {
    const double factor = std::pow(kZoomPerStep, in.scrollSteps);
    const double newClearance = std::clamp(clearance * factor, kMinClearanceM, kMaxAltitudeM);
    const double fraction = 1.0 - newClearance / clearance;
    if (in.cursorLatLon) {
      c.latDeg = std::clamp(c.latDeg + (in.cursorLatLon->x - c.latDeg) * fraction, -89.9, 89.9);
      c.lonDeg = wrap180(c.lonDeg + wrap180(in.cursorLatLon->y - c.lonDeg) * fraction);
    }
    clearance = newClearance;
  }
  // Keys: along the ground, and up and down, at a speed that scales with the clearance.
  const double speed = speedMps(clearance) * (in.fast ? kFastFactor : 1.0) * dtS;
  const double forward = (in.forward ? 1.0 : 0.0) - (in.back ? 1.0 : 0.0);
  const double sideways = (in.right ? 1.0 : 0.0) - (in.left ? 1.0 : 0.0);
  if (forward != 0.0 || sideways != 0.0) {
    const double forwardM = forward * speed, rightM = sideways * speed;
    moveOverGround(c, forwardM * std::sin(heading) + rightM * std::cos(heading),
                   forwardM * std::cos(heading) - rightM * std::sin(heading));
  }
  clearance += ((in.up ? 1.0 : 0.0) - (in.down ? 1.0 : 0.0)) * speed;
  ground = groundAt(c.latDeg, c.lonDeg);
  if (!std::isfinite(ground)) ground = 0.0;
  c.altitudeM = ground + std::clamp(clearance, kMinClearanceM, kMaxAltitudeM);
  c.pitchDeg = -90.0 + (flyPitchDeg_ + 90.0) * flyWeight(clearance);
}

void GlobeCameraController::dropToWalkingHeight(GeoCamera& c, const GlobeGroundFn& groundAt) {
  const double ground = groundAt(c.latDeg, c.lonDeg);
  c.altitudeM = (std::isfinite(ground) ? ground : 0.0) + 2.0;
  flyPitchDeg_ = 0.0;
  c.pitchDeg = 0.0;
}

void GlobeCameraController::frameGlobe(GeoCamera& c) {
  c.altitudeM = 20'000'000.0;
  c.pitchDeg = -90.0;
  c.headingDeg = 0.0;
}

}  // namespace tellus
