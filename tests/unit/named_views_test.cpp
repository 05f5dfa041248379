#include <gtest/gtest.h>

#include <glm/glm.hpp>

#include "tellus/render/output/named_views.hpp"

namespace tellus {
namespace {

HeightGrid hill() {
  HeightGrid grid(201, 101);  // 20 km x 10 km at 100 m
  grid.spacingXM = grid.spacingYM = 100.0;
  for (int row = 0; row < grid.height; ++row) {
    for (int col = 0; col < grid.width; ++col) {
      grid.at(col, row) =
          500.0f + 400.0f * std::sin(float(col) * 0.05f) * std::sin(float(row) * 0.07f);
    }
  }
  return grid;
}

TEST(NamedViews, CameraLookingAtPointsAtTheTarget) {
  const glm::dvec3 eye(100, 200, 300), target(1100, 1200, 300 - std::sqrt(2.0) * 1000);
  const Camera camera = cameraLookingAt(eye, target, 50.0);
  EXPECT_NEAR(camera.yawDeg, 45.0, 1e-9);
  EXPECT_NEAR(camera.pitchDeg, -45.0, 1e-9);
  const glm::dvec3 toTarget = glm::normalize(target - eye);
  EXPECT_NEAR(glm::dot(camera.forward(), toTarget), 1.0, 1e-12);
}

TEST(NamedViews, ObliqueLooksAtTheCentreFromTheSouthEast) {
  const HeightGrid grid = hill();
  const Camera camera = namedView("oblique", grid, 16.0 / 9.0).value();
  const Aabb bounds = grid.worldBounds();
  EXPECT_GT(camera.position.x, bounds.centre().x);
  EXPECT_LT(camera.position.y, bounds.centre().y);
  EXPECT_GT(camera.position.z, bounds.max.z);
  EXPECT_NEAR(camera.pitchDeg, -16.0, 1e-9);
  EXPECT_GT(camera.yawDeg, -90.0);  // heading north-west
  EXPECT_LT(camera.yawDeg, 0.0);
}

TEST(NamedViews, LowViewFliesJustAboveTheGroundLookingNorth) {
  const HeightGrid grid = hill();
  const Camera camera = namedView("low", grid, 16.0 / 9.0).value();
  const double ground = grid.heightAtWorld(camera.position.x, camera.position.y);
  EXPECT_GE(camera.position.z - ground, 30.0);
  EXPECT_LE(camera.position.z - ground, 600.0);
  EXPECT_NEAR(camera.yawDeg, 0.0, 1e-9);
  EXPECT_LT(camera.pitchDeg, 0.0);
  EXPECT_GT(camera.pitchDeg, -20.0);
}

TEST(NamedViews, UnknownNamesAreErrorsListingTheChoices) {
  Result<Camera> camera = namedView("sideways", hill(), 1.0);
  ASSERT_FALSE(camera);
  EXPECT_NE(camera.error().message.find("overview, oblique, low"), std::string::npos)
      << camera.error().message;
}

}  // namespace
}  // namespace tellus
