// Camera paths: keyframe validation and interpolation, JSON round trip, and the built-in paths
// on a real DEM (the orbit looks at the terrain, the flyover and the walk stay above it).
#include <fstream>

#include <gtest/gtest.h>

#include "support/test_support.hpp"
#include "tellus/dem/dem_loader.hpp"
#include "tellus/eval/camera_path.hpp"

namespace tellus {
namespace {

CameraKeyframe key(double t, glm::dvec3 p, double yaw, double pitch = -10.0, double fov = 50.0) {
  CameraKeyframe k;
  k.timeS = t;
  k.camera.position = p;
  k.camera.yawDeg = yaw;
  k.camera.pitchDeg = pitch;
  k.camera.fovYDeg = fov;
  return k;
}

TEST(CameraPath, RejectsBadKeyframes) {
  EXPECT_FALSE(CameraPath::fromKeyframes({key(0, {0, 0, 0}, 0)}));
  EXPECT_FALSE(CameraPath::fromKeyframes({key(0, {0, 0, 0}, 0), key(0, {1, 0, 0}, 0)}));
  EXPECT_FALSE(CameraPath::fromKeyframes({key(0, {0, 0, 0}, 0), key(1, {1, 0, 0}, 0, -10, 0)}));
  EXPECT_FALSE(CameraPath::fromKeyframes({key(0, {0, 0, 0}, 0), key(1, {1, 0, 0}, 0, -95)}));
  EXPECT_FALSE(CameraPath::fromKeyframes({key(0, {0, 0, NAN}, 0), key(1, {1, 0, 0}, 0)}));
}

TEST(CameraPath, PassesThroughItsKeyframesSmoothlyAndTurnsTheShortWay) {
  auto path = CameraPath::fromKeyframes({key(0, {0, 0, 100}, 350), key(2, {100, 0, 100}, 10),
                                         key(3, {100, 100, 150}, 30), key(5, {0, 100, 100}, 90)});
  ASSERT_TRUE(path);
  for (const CameraKeyframe& k : path->keyframes()) {
    const Camera c = path->at(k.timeS);
    EXPECT_NEAR(glm::distance(c.position, k.camera.position), 0.0, 1e-9);
    EXPECT_NEAR(std::fmod(c.yawDeg - k.camera.yawDeg + 720.0, 360.0), 0.0, 1e-9);
  }
  // Between 350 and 10 degrees the heading passes north, not south.
  const double mid = path->at(1.0).yawDeg;
  EXPECT_TRUE(mid > 350.0 || mid < 10.0) << mid;
  // Continuity: small time steps move the camera a little.
  for (double t = 0.0; t < 5.0; t += 0.01) {
    EXPECT_LT(glm::distance(path->at(t).position, path->at(t + 0.01).position), 3.0) << t;
  }
  const std::vector<Camera> frames = path->sample(11);
  ASSERT_EQ(frames.size(), 11u);
  EXPECT_EQ(frames.front().position, glm::dvec3(0, 0, 100));
  EXPECT_NEAR(glm::distance(frames.back().position, glm::dvec3(0, 100, 100)), 0.0, 1e-9);
  EXPECT_EQ(path->at(-3.0).position, frames.front().position);  // clamped
}

TEST(CameraPath, SavesAndLoadsKeyframeJson) {
  auto path = CameraPath::fromKeyframes({key(0, {1, 2, 3}, 45, -20, 40), key(1.5, {4, 5, 6}, 90)});
  ASSERT_TRUE(path);
  const std::filesystem::path file = test::freshTestDir() / "path.json";
  ASSERT_TRUE(saveCameraPath(path.value(), file));
  Result<CameraPath> loaded = makeCameraPath(file.string(), HeightGrid(2, 2));
  ASSERT_TRUE(loaded) << loaded.error().message;
  ASSERT_EQ(loaded->keyframes().size(), 2u);
  EXPECT_EQ(loaded->keyframes()[1].timeS, 1.5);
  EXPECT_EQ(loaded->keyframes()[0].camera.fovYDeg, 40.0);
  EXPECT_EQ(loaded->keyframes()[1].camera.position, glm::dvec3(4, 5, 6));

  std::ofstream(file) << R"({"keyframes": [{"time": 0, "position": [0, 0]}]})";
  Result<CameraPath> bad = loadCameraPath(file);
  ASSERT_FALSE(bad);
  EXPECT_NE(bad.error().message.find("path.json"), std::string::npos) << bad.error().message;
  EXPECT_FALSE(makeCameraPath("spiral", HeightGrid(2, 2)));
}

TEST(CameraPath, BuiltInPathsFrameTheTerrainAndStayAboveIt) {
  TELLUS_REQUIRE_SHARED_DATA(data);
  Result<HeightGrid> grid = loadDem({data / "srtm3-hgt-east-asia/N36E137.hgt"});  // Japan Alps
  ASSERT_TRUE(grid);
  const double width = (grid->width - 1) * grid->spacingXM;

  Result<CameraPath> orbit = makeCameraPath("orbit", grid.value());
  ASSERT_TRUE(orbit);
  const Aabb bounds = grid->worldBounds();
  for (const Camera& c : orbit->sample(24)) {
    ViewSetup view = ViewSetup::create(c, bounds, 400, 300);
    glm::dvec2 pixel;
    const glm::dvec3 centre{0.5 * width, 0.5 * (grid->height - 1) * grid->spacingYM,
                            0.5 * (bounds.min.z + bounds.max.z)};
    ASSERT_TRUE(view.projectToPixel(centre, pixel));
    EXPECT_NEAR(pixel.x, 200.0, 2.0);
    EXPECT_NEAR(pixel.y, 150.0, 40.0);
  }

  Result<CameraPath> flyover = makeCameraPath("flyover", grid.value());
  ASSERT_TRUE(flyover);
  const std::vector<Camera> flight = flyover->sample(200);
  EXPECT_GT(glm::distance(flight.front().position, flight.back().position), 0.8 * width);
  for (const Camera& c : flight) {
    const double clearance =
        c.position.z - groundUpperBound(grid.value(), c.position.x, c.position.y);
    EXPECT_GT(clearance, 100.0);
    EXPECT_LT(clearance, 3000.0);
  }

  Result<CameraPath> walk = makeCameraPath("walk", grid.value());
  ASSERT_TRUE(walk);
  const std::vector<Camera> steps = walk->sample(300);
  EXPECT_NEAR(glm::distance(steps.front().position, steps.back().position), 2000.0, 300.0);
  for (const Camera& c : steps) {
    const double clearance =
        c.position.z - groundUpperBound(grid.value(), c.position.x, c.position.y);
    EXPECT_GT(clearance, 1.0);   // above the mesh
    EXPECT_LT(clearance, 40.0);  // and walking on it, not flying
  }
  // Deterministic.
  EXPECT_EQ(makeCameraPath("walk", grid.value())->sample(300)[123].position, steps[123].position);

  // Seed 004's rotation: one position above the ground, 360 one-degree steps.
  Result<CameraPath> rotate = makeCameraPath("rotate", grid.value());
  ASSERT_TRUE(rotate);
  const std::vector<Camera> turn = rotate->sample(360);
  ASSERT_EQ(turn.size(), 360u);
  for (int i = 0; i < 360; ++i) {
    EXPECT_NEAR(turn[std::size_t(i)].yawDeg, double(i), 1e-9);
    EXPECT_LT(glm::distance(turn[std::size_t(i)].position, turn[0].position), 1e-6);
  }
  EXPECT_GT(turn[0].position.z - groundUpperBound(grid.value(), turn[0].position.x,
                                                  turn[0].position.y),
            1.0);
}

}  // namespace
}  // namespace tellus
