// The viewer's camera on the globe (GL-free): orbiting high up, flying near the ground, the
// blend between, zooming towards the cursor, and never below the ground.
#include <cmath>

#include <gtest/gtest.h>

#include "tellus/viewer/globe_camera.hpp"

namespace tellus {
namespace {

const GlobeGroundFn kHills = [](double lat, double lon) {
  return 800.0 + 300.0 * std::sin(lat * 40.0) * std::cos(lon * 30.0);
};

TEST(GlobeCamera, OrbitsHighAndFliesLow) {
  EXPECT_EQ(GlobeCameraController::flyWeight(1e7), 0.0);
  EXPECT_EQ(GlobeCameraController::flyWeight(GlobeCameraController::kOrbitAboveM), 0.0);
  EXPECT_EQ(GlobeCameraController::flyWeight(GlobeCameraController::kFlyBelowM), 1.0);
  EXPECT_EQ(GlobeCameraController::flyWeight(2.0), 1.0);
  const double middle = GlobeCameraController::flyWeight(std::sqrt(
      GlobeCameraController::kOrbitAboveM * GlobeCameraController::kFlyBelowM));
  EXPECT_NEAR(middle, 0.5, 1e-9);

  GlobeCameraController controller;
  controller.setFlyPitchDeg(-20.0);
  GeoCamera c{35.0, 127.0, 5'000'000.0, 0.0, -90.0, 45.0};
  controller.update(c, {}, 0.016, 720, kHills);
  EXPECT_EQ(c.pitchDeg, -90.0) << "straight down from orbit";
  // Dragging the mouse down by 100 px pulls the ground down: the camera moves north by about
  // 100 px worth of ground at the nadir, the view does not turn.
  GlobeInput drag;
  drag.dragPx = {0.0, 100.0};
  const double clearance = c.altitudeM - kHills(c.latDeg, c.lonDeg);
  const double expectedM = 100.0 * 2.0 * clearance * std::tan(22.5 * M_PI / 180.0) / 720.0;
  controller.update(c, drag, 0.016, 720, kHills);
  EXPECT_NEAR((c.latDeg - 35.0) * 111'320.0, expectedM, 1e-6 * expectedM);
  EXPECT_NEAR(c.lonDeg, 127.0, 1e-9);
  EXPECT_EQ(c.headingDeg, 0.0);

  // Near the ground, the same drag looks down instead, and keys move along the heading.
  GeoCamera low{35.0, 127.0, kHills(35.0, 127.0) + 100.0, 90.0, 0.0, 60.0};
  controller.setFlyPitchDeg(0.0);
  controller.update(low, drag, 0.016, 720, kHills);
  EXPECT_NEAR(low.latDeg, 35.0, 1e-12);
  EXPECT_NEAR(low.pitchDeg, -15.0, 1e-9);
  GlobeInput walkEast;
  walkEast.forward = true;
  const double lonBefore = low.lonDeg;
  controller.update(low, walkEast, 1.0, 720, kHills);
  EXPECT_GT(low.lonDeg, lonBefore) << "heading 90 walks east";
  EXPECT_NEAR(low.latDeg, 35.0, 1e-9);
  EXPECT_NEAR(low.altitudeM - kHills(low.latDeg, low.lonDeg), 100.0, 1e-6)
      << "the height above the ground is kept";
}

TEST(GlobeCamera, ZoomsTowardsTheCursorAndStaysAboveTheGround) {
  GlobeCameraController controller;
  GeoCamera c{35.0, 127.0, 1'000'000.0, 0.0, -90.0, 45.0};
  const double clearance = c.altitudeM - kHills(35.0, 127.0);
  GlobeInput zoom;
  zoom.scrollSteps = 1.0;
  zoom.cursorLatLon = glm::dvec2(36.0, 128.0);
  controller.update(c, zoom, 0.016, 720, kHills);
  EXPECT_NEAR(c.latDeg, 35.2, 1e-9) << "a fifth of the way to the cursor's point";
  EXPECT_NEAR(c.lonDeg, 127.2, 1e-9);
  EXPECT_NEAR(c.altitudeM - kHills(c.latDeg, c.lonDeg), 0.8 * clearance, 1e-6 * clearance);
  // Zooming in a long way ends 2 m above the ground, never under it.
  zoom.scrollSteps = 200.0;
  zoom.cursorLatLon.reset();
  controller.update(c, zoom, 0.016, 720, kHills);
  EXPECT_NEAR(c.altitudeM - kHills(c.latDeg, c.lonDeg), GlobeCameraController::kMinClearanceM,
              1e-9);
  GlobeInput down;
  down.down = true;
  controller.update(c, down, 10.0, 720, kHills);
  EXPECT_GE(c.altitudeM - kHills(c.latDeg, c.lonDeg), GlobeCameraController::kMinClearanceM);
  // Out again, and the whole globe.
  controller.frameGlobe(c);
  EXPECT_EQ(c.altitudeM, 20'000'000.0);
  controller.dropToWalkingHeight(c, kHills);
  EXPECT_NEAR(c.altitudeM, kHills(c.latDeg, c.lonDeg) + 2.0, 1e-9);
  EXPECT_EQ(c.pitchDeg, 0.0);
  // Across the antimeridian longitude wraps.
  GeoCamera east{0.0, 179.99, 20'000.0, 90.0, -45.0, 45.0};
  GlobeInput forward;
  forward.forward = true;
  controller.update(east, forward, 1.0, 720, kHills);
  EXPECT_LT(east.lonDeg, -179.0);
}

}  // namespace
}  // namespace tellus
