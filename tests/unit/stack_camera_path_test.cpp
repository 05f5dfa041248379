// The cave walk (bench --path cave) on a synthetic L-shaped tunnel: it walks the tunnel from one
// end to the other and keeps clear of its walls, so that the camera's near plane never cuts
// into the rock (a shortest path alone hugs the inner corner).
#include <gtest/gtest.h>

#include <cmath>

#include "tellus/eval/stack_camera_path.hpp"
#include "tellus/formats/stacks/stack_generator.hpp"

namespace tellus {
namespace {

constexpr int kSize = 40;
constexpr double kSpacingM = 2.0;

// Tunnel columns (x, row): a leg 9 columns wide down rows 5..34 at x 5..13, and one along rows
// 26..34 to x 34. Its air gap runs from 10 m to 20 m; everything else is rock to 30 m.
bool inTunnel(int x, int row) {
  const bool down = x >= 5 && x <= 13 && row >= 5 && row <= 34;
  const bool across = row >= 26 && row <= 34 && x >= 5 && x <= 34;
  return down || across;
}

StackTerrain tunnelTerrain() {
  std::vector<std::vector<StackLayer>> columns;
  for (int row = 0; row < kSize; ++row) {
    for (int x = 0; x < kSize; ++x) {
      if (inTunnel(x, row)) {
        columns.push_back({{0.0f, 10.0f, kStackRock}, {20.0f, 30.0f, kStackRock}});
      } else {
        columns.push_back({{0.0f, 30.0f, kStackRock}});
      }
    }
  }
  Result<StackTerrain> terrain = StackTerrain::fromColumns(kSize, kSize, kSpacingM, columns);
  EXPECT_TRUE(terrain) << terrain.error().message;
  return std::move(terrain.value());
}

TEST(CavePath, WalksTheTunnelEndToEndClearOfItsWalls) {
  const StackTerrain terrain = tunnelTerrain();
  StackPassage passage;
  Result<CameraPath> path = makeCavePath(terrain, 6.0, &passage);
  ASSERT_TRUE(path) << path.error().message;
  EXPECT_EQ(passage.columns, std::size_t(9 * 30 + 9 * 21));
  EXPECT_NEAR(passage.meanGapM, 10.0, 1e-6);
  EXPECT_GT(passage.lengthM, 60.0 * kSpacingM * 0.6);  // most of the L, end to end
  for (const Camera& camera : path->sample(300)) {
    const double column = camera.position.x / kSpacingM;
    const double row = kSize - 1 - camera.position.y / kSpacingM;
    // Every column within 1.5 columns of the camera is tunnel: no rock within 3 m sideways.
    for (double dy = -1.5; dy <= 1.5; dy += 0.5) {
      for (double dx = -1.5; dx <= 1.5; dx += 0.5) {
        const int x = int(std::lround(column + dx)), r = int(std::lround(row + dy));
        EXPECT_TRUE(inTunnel(x, r)) << "camera at " << camera.position.x << ", "
                                    << camera.position.y << ": rock at column " << x << ", row " << r;
      }
    }
    EXPECT_GT(camera.position.z, 12.0);
    EXPECT_LT(camera.position.z, 18.0);
  }
}

TEST(CavePath, RefusesTerrainWithoutAPassage) {
  std::vector<std::vector<StackLayer>> columns(16, {{0.0f, 5.0f, kStackRock}});
  Result<StackTerrain> terrain = StackTerrain::fromColumns(4, 4, kSpacingM, columns);
  ASSERT_TRUE(terrain);
  Result<CameraPath> path = makeCavePath(terrain.value());
  ASSERT_FALSE(path);
  EXPECT_NE(path.error().message.find("no cave or arch opening"), std::string::npos);
}

}  // namespace
}  // namespace tellus
