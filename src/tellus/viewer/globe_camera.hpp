#pragma once
// The viewer's camera on the globe, free of GLFW and GL so that it can be tested. High up it
// orbits: dragging turns the globe under the cursor, the wheel zooms exponentially towards the
// point under the cursor, and the view looks straight down. Near the ground it flies: dragging
// looks around, W A S D move along the ground at a speed that scales with the height above it,
// Q E go down and up. Between kOrbitAboveM and kFlyBelowM (on a log scale of the clearance) the
// two blend: the pitch turns from straight down to the flyer's own, and dragging from turning
// the globe to looking around. The camera never goes below the ground plus kMinClearanceM.
#include <functional>
#include <optional>

#include <glm/vec2.hpp>

#include "tellus/core/geo_camera.hpp"

namespace tellus {

struct GlobeInput {
  glm::dvec2 dragPx{0.0, 0.0};  // mouse movement while a button is held (x right, y down)
  double scrollSteps = 0.0;     // wheel steps, positive away from the user (zoom in)
  // Latitude and longitude (degrees) of the ground under the cursor, when it is over the globe.
  std::optional<glm::dvec2> cursorLatLon;
  bool forward = false, back = false, left = false, right = false;
  bool down = false, up = false;
  bool fast = false;  // Shift held
};

// Ellipsoidal height of the ground at (lat, lon), metres.
using GlobeGroundFn = std::function<double(double latDeg, double lonDeg)>;

class GlobeCameraController {
 public:
  static constexpr double kOrbitAboveM = 200'000.0;
  static constexpr double kFlyBelowM = 10'000.0;
  static constexpr double kMinClearanceM = 2.0;
  static constexpr double kZoomPerStep = 0.8;  // clearance factor per wheel step in
  static constexpr double kLookDegPerPx = 0.15;
  static constexpr double kFastFactor = 4.0;
  static constexpr double kMaxAltitudeM = 50'000'000.0;

  // 0 when orbiting, 1 when flying, smooth in between (log of the clearance).
  static double flyWeight(double clearanceM);

  // One frame: `camera` turns, zooms and moves by `input` over `dtS` seconds in a view
  // `viewHeightPx` pixels tall; its pitch follows the blend.
  void update(GeoCamera& camera, const GlobeInput& input, double dtS, int viewHeightPx,
              const GlobeGroundFn& groundAt);

  // The flyer's pitch, used as the blend reaches the ground (degrees).
  double flyPitchDeg() const { return flyPitchDeg_; }
  void setFlyPitchDeg(double pitchDeg);
  // Metres per second at `clearanceM` above the ground (without Shift).
  static double speedMps(double clearanceM) { return std::max(clearanceM, 2.0); }

  // Down to walking height (2 m) looking level; and the whole globe in view from 20,000 km.
  void dropToWalkingHeight(GeoCamera& camera, const GlobeGroundFn& groundAt);
  void frameGlobe(GeoCamera& camera);

 private:
  double flyPitchDeg_ = -20.0;
};

}  // namespace tellus
