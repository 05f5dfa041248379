// Frustum culling of boxes with the renderers' camera-relative reversed-Z matrices, one by one
// (Frustum) and many at once (BoxCullSet).
#include <cmath>
#include <random>
#include <vector>

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include "tellus/core/box_cull_set.hpp"
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

namespace tellus {
namespace {

// BoxCullSet (the vectorised test the stack renderer culls its selections with) against
// Frustum::intersects, on random views and boxes of every size over a 40 km terrain, with and
// without vertical exaggeration: every box intersects keeps is kept, and a box kept beyond it
// lies outside by less than the set's float slack (it is kept once widened by a few millionths
// of the farthest distance in the set: centimetres at 50 km).
TEST(BoxCullSet, AgreesWithFrustumIntersects) {
  std::mt19937 random(17);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::vector<Aabb> boxes;
  for (int i = 0; i < 20000; ++i) {
    const glm::dvec3 centre(40000.0 * unit(random), 40000.0 * unit(random), 3000.0 * unit(random));
    const double half = std::pow(10.0, 4.0 * unit(random) - 1.0);  // 0.1 m to 1 km
    boxes.push_back({centre - glm::dvec3(half, half, 0.3 * half), centre + glm::dvec3(half, half, 0.3 * half)});
  }
  const BoxCullSet set(boxes);
  ASSERT_EQ(set.size(), boxes.size());
  const Aabb world{{0.0, 0.0, 0.0}, {40000.0, 40000.0, 3000.0}};
  std::size_t kept = 0, dropped = 0, extra = 0;
  for (int v = 0; v < 40; ++v) {
    Camera camera;
    camera.position = {40000.0 * unit(random), 40000.0 * unit(random), 200.0 + 5000.0 * unit(random)};
    camera.yawDeg = 360.0 * unit(random);
    camera.pitchDeg = -80.0 * unit(random);
    camera.fovYDeg = 30.0 + 40.0 * unit(random);
    const double exaggeration = v % 3 == 0 ? 2.5 : 1.0;
    const ViewSetup view = ViewSetup::create(camera, world, 1280, 720);
    const Frustum frustum = Frustum::fromMatrix(view.relativeViewProjection());
    std::vector<std::uint8_t> flags;
    set.markInside(frustum, camera.position, exaggeration, 2, flags);
    ASSERT_EQ(flags.size(), boxes.size());
    for (std::size_t i = 0; i < boxes.size(); ++i) {
      Aabb relative = boxes[i];
      relative.min.z *= exaggeration;
      relative.max.z *= exaggeration;
      relative.min -= camera.position;
      relative.max -= camera.position;
      const bool expected = frustum.intersects(relative);
      const bool got = flags[i] == 2;
      if (expected) {
        ASSERT_TRUE(got) << "view " << v << ", box " << i << " dropped";
        ++kept;
        continue;
      }
      ++dropped;
      if (!got) continue;
      ++extra;
      // The set's slack: a millionth of the farthest distance in it (a few, for the test).
      const double reach = glm::length(world.centre() - camera.position) +
                           0.5 * glm::length(world.size()) * std::max(1.0, exaggeration);
      const double widen = 3e-6 * reach + 1e-3;
      relative.min -= glm::dvec3(widen);
      relative.max += glm::dvec3(widen);
      EXPECT_TRUE(frustum.intersects(relative)) << "view " << v << ", box " << i << " kept far outside";
    }
  }
  EXPECT_GT(kept, 20000u);      // both answers occur often
  EXPECT_GT(dropped, 200000u);
  EXPECT_LT(extra, kept / 1000 + 10);  // rounding keeps almost nothing extra
}

TEST(BoxCullSet, AnEmptySetMarksNothingAndOrsIntoExistingFlags) {
  std::vector<std::uint8_t> flags;
  BoxCullSet().markInside(Frustum{}, glm::dvec3(0.0), 1.0, 1, flags);
  EXPECT_TRUE(flags.empty());
  const BoxCullSet one(std::vector<Aabb>{Aabb{{-1.0, -1.0, -1.0}, {1.0, 1.0, 1.0}}});
  flags = {4};
  one.markInside(Frustum{}, glm::dvec3(0.0), 1.0, 1, flags);  // all-zero planes: inside
  EXPECT_EQ(flags[0], 5);
}

}  // namespace
}  // namespace tellus
