#include <gtest/gtest.h>

#include <glm/glm.hpp>

#include "tellus/core/camera.hpp"

namespace tellus {
namespace {

void expectNear(const glm::dvec3& a, const glm::dvec3& b, double tolerance = 1e-9) {
  EXPECT_NEAR(a.x, b.x, tolerance);
  EXPECT_NEAR(a.y, b.y, tolerance);
  EXPECT_NEAR(a.z, b.z, tolerance);
}

TEST(CameraParse, AcceptsSixNumbers) {
  Result<Camera> camera = parseCamera("100.5, -20,3000,45,-30.5,60");
  ASSERT_TRUE(camera) << camera.error().message;
  expectNear(camera->position, {100.5, -20.0, 3000.0});
  EXPECT_DOUBLE_EQ(camera->yawDeg, 45.0);
  EXPECT_DOUBLE_EQ(camera->pitchDeg, -30.5);
  EXPECT_DOUBLE_EQ(camera->fovYDeg, 60.0);
}

TEST(CameraParse, RejectsBadStringsNamingTheField) {
  EXPECT_NE(parseCamera("1,2,3,4,5").error().message.find("expected 6"), std::string::npos);
  EXPECT_NE(parseCamera("1,2,3,4,5,6,7").error().message.find("expected 6"), std::string::npos);
  EXPECT_NE(parseCamera("1,2,abc,4,5,6").error().message.find("field 3 (z)"), std::string::npos);
  EXPECT_NE(parseCamera("1,2,3,4,5,").error().message.find("field 6 (fov)"), std::string::npos);
  EXPECT_NE(parseCamera("1,2,3,4,-91,60").error().message.find("pitch"), std::string::npos);
  EXPECT_NE(parseCamera("1,2,3,4,5,180").error().message.find("fov"), std::string::npos);
  EXPECT_FALSE(parseCamera("1,2,3,4,5,nan"));
  EXPECT_FALSE(parseCamera(""));
}

TEST(CameraFrame, YawIsACompassHeadingAndPitchTiltsUp) {
  Camera camera;
  expectNear(camera.forward(), {0, 1, 0});  // north
  expectNear(camera.right(), {1, 0, 0});    // east
  expectNear(camera.up(), {0, 0, 1});
  camera.yawDeg = 90.0;
  expectNear(camera.forward(), {1, 0, 0});  // east
  expectNear(camera.right(), {0, -1, 0});   // south
  camera.yawDeg = 0.0;
  camera.pitchDeg = -90.0;  // straight down stays well defined
  expectNear(camera.forward(), {0, 0, -1});
  expectNear(camera.right(), {1, 0, 0});
  expectNear(camera.up(), {0, 1, 0});
}

TEST(CameraFrame, ViewRotationMapsTheFrameToEyeSpace) {
  Camera camera;
  camera.yawDeg = 30.0;
  camera.pitchDeg = -20.0;
  const glm::dmat4 view = viewRotation(camera);
  expectNear(glm::dvec3(view * glm::dvec4(camera.forward(), 0.0)), {0, 0, -1});
  expectNear(glm::dvec3(view * glm::dvec4(camera.right(), 0.0)), {1, 0, 0});
  expectNear(glm::dvec3(view * glm::dvec4(camera.up(), 0.0)), {0, 1, 0});
}

TEST(CameraProjection, ReversedZPutsNearAtOneAndFarAtZero) {
  const ClipRange clip{2.0, 5000.0};
  const glm::dmat4 p = reversedZProjection(60.0, 1.5, clip);
  const auto depthAt = [&](double distance) {
    const glm::dvec4 c = p * glm::dvec4(0, 0, -distance, 1);
    return c.z / c.w;
  };
  EXPECT_NEAR(depthAt(2.0), 1.0, 1e-12);
  EXPECT_NEAR(depthAt(5000.0), 0.0, 1e-12);
  EXPECT_GT(depthAt(10.0), depthAt(100.0));  // nearer is larger
}

TEST(CameraProjection, ProjectsToTheExpectedPixels) {
  Camera camera;
  camera.position = {1000.0, 2000.0, 500.0};
  camera.fovYDeg = 90.0;  // tan(45) = 1: the image edges are at 45 degrees
  const Aabb bounds{{0, 0, 0}, {5000, 5000, 1000}};
  const ViewSetup view = ViewSetup::create(camera, bounds, 200, 100);  // aspect 2
  glm::dvec2 pixel;
  ASSERT_TRUE(view.projectToPixel(camera.position + glm::dvec3(0, 100, 0), pixel));
  EXPECT_NEAR(pixel.x, 100.0, 1e-9);
  EXPECT_NEAR(pixel.y, 50.0, 1e-9);
  // 45 degrees up is the top edge; 63.4 degrees right (tan = 2 = aspect) is the right edge.
  ASSERT_TRUE(view.projectToPixel(camera.position + glm::dvec3(0, 100, 100), pixel));
  EXPECT_NEAR(pixel.y, 0.0, 1e-9);
  ASSERT_TRUE(view.projectToPixel(camera.position + glm::dvec3(200, 100, 0), pixel));
  EXPECT_NEAR(pixel.x, 200.0, 1e-9);
  EXPECT_FALSE(view.projectToPixel(camera.position + glm::dvec3(0, -100, 0), pixel));  // behind
}

TEST(CameraClipRange, CoversTheBoxFromOutsideAndInside) {
  const Aabb bounds{{0, 0, 0}, {1000, 1000, 100}};
  Camera outside;
  outside.position = {500, -1000, 100};
  ClipRange clip = chooseClipRange(outside, bounds);
  EXPECT_NEAR(clip.nearM, 500.0, 1e-9);  // half the distance to the box
  EXPECT_GE(clip.farM, glm::length(glm::dvec3(1000, 1000, 0) - outside.position));
  Camera inside;
  inside.position = {500, 500, 50};
  clip = chooseClipRange(inside, bounds);
  EXPECT_DOUBLE_EQ(clip.nearM, 0.5);
  EXPECT_GE(clip.farM, glm::length(glm::dvec3(0, 0, 0) - inside.position));
}

TEST(CameraOverview, FramesEveryCornerTightly) {
  const Aabb bounds{{0, 0, -50}, {360000, 440000, 1900}};
  const Camera camera = overviewCamera(bounds, 16.0 / 9.0);
  const ViewSetup view = ViewSetup::create(camera, bounds, 1600, 900);
  double largestNdc = 0.0;
  for (const glm::dvec3& corner : bounds.corners()) {
    glm::dvec2 pixel;
    ASSERT_TRUE(view.projectToPixel(corner, pixel));
    const double nx = pixel.x / 800.0 - 1.0, ny = pixel.y / 450.0 - 1.0;
    EXPECT_LE(std::abs(nx), 0.9 + 1e-6);
    EXPECT_LE(std::abs(ny), 0.9 + 1e-6);
    largestNdc = std::max({largestNdc, std::abs(nx), std::abs(ny)});
  }
  EXPECT_GT(largestNdc, 0.89);  // no closer camera would fit
}

}  // namespace
}  // namespace tellus
