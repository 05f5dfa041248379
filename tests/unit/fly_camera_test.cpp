// The viewer's fly camera: WASD/QE move along the view, sideways and vertically at a speed
// that scales with the height above the ground, the wheel changes the speed, mouse look turns
// and clamps the pitch, the camera stays above the ground, G drops to eye height and F frames
// the whole terrain.
#include <gtest/gtest.h>

#include <glm/geometric.hpp>

#include "tellus/viewer/fly_camera.hpp"

namespace tellus {
namespace {

Camera cameraAt(glm::dvec3 position, double yaw = 0.0, double pitch = 0.0) {
  Camera c;
  c.position = position;
  c.yawDeg = yaw;
  c.pitchDeg = pitch;
  return c;
}

const auto kFlatGround = [](double, double) { return 100.0; };

TEST(FlyCamera, WasdMovesAlongTheViewAndSidewaysQeDownAndUp) {
  FlyCameraController controller;
  FlyInput forward;
  forward.forward = true;
  Camera c = cameraAt({0, 0, 1100}, 90.0);  // looking east, 1000 m above the ground
  controller.update(c, forward, 0.5, kFlatGround);
  EXPECT_NEAR(c.position.x, 500.0, 1e-9);  // 1000 m/s for half a second
  EXPECT_NEAR(c.position.y, 0.0, 1e-9);
  EXPECT_NEAR(c.position.z, 1100.0, 1e-9);

  FlyInput left;
  left.left = true;
  c = cameraAt({0, 0, 1100}, 90.0);
  controller.update(c, left, 0.1, kFlatGround);
  EXPECT_NEAR(c.position.y, 100.0, 1e-9);  // looking east, left is north

  FlyInput up;
  up.up = true;
  c = cameraAt({0, 0, 1100}, 90.0, -30.0);
  controller.update(c, up, 0.1, kFlatGround);
  EXPECT_NEAR(c.position.z, 1200.0, 1e-9);  // straight up whatever the pitch

  // Forward and right together move at the same speed, diagonally.
  FlyInput diagonal;
  diagonal.forward = diagonal.right = true;
  c = cameraAt({0, 0, 1100}, 0.0);
  controller.update(c, diagonal, 0.1, kFlatGround);
  EXPECT_NEAR(glm::length(c.position - glm::dvec3(0, 0, 1100)), 100.0, 1e-9);
  EXPECT_NEAR(c.position.x, c.position.y, 1e-9);  // north-east
}

TEST(FlyCamera, SpeedScalesWithHeightAboveGroundAndTheWheel) {
  FlyCameraController controller;
  EXPECT_DOUBLE_EQ(controller.speedMps(5000.0), 5000.0);
  EXPECT_DOUBLE_EQ(controller.speedMps(0.0), FlyCameraController::kMinSpeedMps);
  FlyInput wheel;
  wheel.scrollSteps = 2.0;
  Camera c = cameraAt({0, 0, 1100});
  controller.update(c, wheel, 0.0, kFlatGround);
  EXPECT_NEAR(controller.speedFactor(), 1.5625, 1e-12);
  EXPECT_NEAR(controller.speedMps(1000.0), 1562.5, 1e-9);
  wheel.scrollSteps = -4.0;
  controller.update(c, wheel, 0.0, kFlatGround);
  EXPECT_NEAR(controller.speedFactor(), 1.0 / 1.5625, 1e-12);

  // Shift: four times faster.
  FlyCameraController plain;
  FlyInput fast;
  fast.forward = fast.fast = true;
  c = cameraAt({0, 0, 200});
  plain.update(c, fast, 1.0, kFlatGround);
  EXPECT_NEAR(c.position.y, 400.0, 1e-9);
}

TEST(FlyCamera, MouseLookTurnsAndClampsThePitch) {
  FlyCameraController controller;
  FlyInput look;
  look.mouseDeltaPx = {100.0, 0.0};  // right: turn clockwise
  Camera c = cameraAt({0, 0, 1100}, 350.0);
  controller.update(c, look, 0.016, kFlatGround);
  EXPECT_NEAR(c.yawDeg, 5.0, 1e-9);    // 350 + 15, wrapped
  look.mouseDeltaPx = {0.0, 10000.0};  // far down
  controller.update(c, look, 0.016, kFlatGround);
  EXPECT_DOUBLE_EQ(c.pitchDeg, -89.0);
  EXPECT_EQ(c.position, glm::dvec3(0, 0, 1100));  // looking does not move
}

TEST(FlyCamera, StaysAboveTheGroundAndDropsToWalkingHeight) {
  FlyCameraController controller;
  FlyInput down;
  down.down = true;
  Camera c = cameraAt({0, 0, 110});
  // A hill rises to 500 m east of x = 50.
  const auto hill = [](double x, double) { return x > 50.0 ? 500.0 : 100.0; };
  controller.update(c, down, 10.0, hill);
  EXPECT_DOUBLE_EQ(c.position.z, 100.0 + FlyCameraController::kMinClearanceM);
  c.position.x = 60.0;
  controller.update(c, FlyInput{}, 0.016, hill);
  EXPECT_DOUBLE_EQ(c.position.z, 500.0 + FlyCameraController::kMinClearanceM);

  c = cameraAt({0, 0, 3000}, 45.0, -40.0);
  FlyCameraController::dropToWalkingHeight(c, 250.0);
  EXPECT_DOUBLE_EQ(c.position.z, 250.0 + FlyCameraController::kWalkEyeHeightM);
  EXPECT_DOUBLE_EQ(c.pitchDeg, 0.0);
  EXPECT_DOUBLE_EQ(c.yawDeg, 45.0);
}

TEST(FlyCamera, FrameAllKeepsTheHeadingAndSeesEveryCorner) {
  Aabb bounds;
  bounds.min = {0, 0, 0};
  bounds.max = {50000, 30000, 2000};
  const Camera c = FlyCameraController::frameAll(bounds, 16.0 / 9.0, 45.0, 120.0);
  EXPECT_DOUBLE_EQ(c.yawDeg, 120.0);
  EXPECT_DOUBLE_EQ(c.pitchDeg, -45.0);
  const ViewSetup view = ViewSetup::create(c, bounds, 1600, 900);
  for (const glm::dvec3& corner : bounds.corners()) {
    glm::dvec2 pixel;
    ASSERT_TRUE(view.projectToPixel(corner, pixel));
    EXPECT_GE(pixel.x, 0.0);
    EXPECT_LE(pixel.x, 1600.0);
    EXPECT_GE(pixel.y, 0.0);
    EXPECT_LE(pixel.y, 900.0);
  }
}

}  // namespace
}  // namespace tellus
