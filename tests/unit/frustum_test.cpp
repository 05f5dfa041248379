// Frustum culling of boxes with the renderers' camera-relative reversed-Z matrices.
#include <gtest/gtest.h>

#include "tellus/core/camera.hpp"
#include "tellus/core/frustum.hpp"

namespace tellus {
namespace {

Aabb boxAround(const glm::dvec3& centre, double halfSize) {
  return {centre - glm::dvec3(halfSize), centre + glm::dvec3(halfSize)};
}

TEST(Frustum, KeepsWhatTheCameraSeesAndDropsTheRest) {
  Camera camera;
  camera.position = {1000.0, 2000.0, 500.0};
  camera.yawDeg = 90.0;  // looking east
  camera.pitchDeg = 0.0;
  camera.fovYDeg = 60.0;
  const Aabb world{{-1e5, -1e5, -100.0}, {1e5, 1e5, 3000.0}};
  const ViewSetup view = ViewSetup::create(camera, world, 1600, 900);
  const Frustum frustum = Frustum::fromMatrix(view.relativeViewProjection());
  // Camera-relative boxes.
  EXPECT_TRUE(frustum.intersects(boxAround({1000.0, 0.0, 0.0}, 10.0)));      // ahead
  EXPECT_FALSE(frustum.intersects(boxAround({-1000.0, 0.0, 0.0}, 10.0)));    // behind
  EXPECT_FALSE(frustum.intersects(boxAround({1000.0, 2000.0, 0.0}, 10.0)));  // far to the left
  EXPECT_FALSE(frustum.intersects(boxAround({1000.0, 0.0, 1500.0}, 10.0)));  // above the top
  EXPECT_TRUE(frustum.intersects(boxAround({1000.0, 0.0, 560.0}, 10.0)));    // near the top edge
  EXPECT_TRUE(frustum.intersects(boxAround({0.0, 0.0, 0.0}, 5.0)));          // around the eye
  // A long box crossing the view from left to right with no corner inside.
  EXPECT_TRUE(frustum.intersects(Aabb{{500.0, -1e4, -10.0}, {520.0, 1e4, 10.0}}));
  // Beyond the far plane.
  EXPECT_FALSE(frustum.intersects(boxAround({view.clip.farM * 1.5, 0.0, 0.0}, 10.0)));
}

}  // namespace
}  // namespace tellus
