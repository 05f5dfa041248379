// Geometry image warping's GL-free parts (seed 004 section 2.4): the row-then-column warp keeps
// the grid's corners and borders, never folds a quad over (every triangle of the warped quad
// mesh keeps its orientation) and moves samples towards importance; the view's region encloses
// what the frustum sees of the terrain.
#include <algorithm>
#include <random>

#include <gtest/gtest.h>

#include "tellus/core/camera.hpp"
#include "tellus/dem/terrain_generator.hpp"
#include "tellus/lod/giw/giw_warp.hpp"

namespace tellus::giw {
namespace {

double orient(glm::dvec2 a, glm::dvec2 b, glm::dvec2 c) {
  return (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x);
}

void expectNoFold(const std::vector<glm::dvec2>& warped, int n) {
  for (int j = 0; j + 1 < n; ++j) {
    for (int i = 0; i + 1 < n; ++i) {
      const auto at = [&](int x, int y) { return warped[std::size_t(y) * std::size_t(n) + std::size_t(x)]; };
      ASSERT_GT(orient(at(i, j), at(i + 1, j), at(i + 1, j + 1)), 0.0) << i << "," << j;
      ASSERT_GT(orient(at(i, j), at(i + 1, j + 1), at(i, j + 1)), 0.0) << i << "," << j;
    }
  }
}

TEST(GiwWarp, KeepsCornersAndBordersAndNeverFolds) {
  const int n = 65;
  std::mt19937 rng(7);
  std::lognormal_distribution<float> spread(0.0f, 2.0f);  // importance over several decades
  for (int trial = 0; trial < 20; ++trial) {
    std::vector<float> importance(std::size_t(n) * std::size_t(n));
    for (float& v : importance) v = spread(rng);
    const std::vector<glm::dvec2> warped = warpRowsThenColumns(importance, n, trial % 2 ? 0.0f : 0.1f);
    const auto at = [&](int x, int y) { return warped[std::size_t(y) * std::size_t(n) + std::size_t(x)]; };
    EXPECT_EQ(at(0, 0), glm::dvec2(0, 0));
    EXPECT_EQ(at(n - 1, 0), glm::dvec2(n - 1, 0));
    EXPECT_EQ(at(0, n - 1), glm::dvec2(0, n - 1));
    EXPECT_EQ(at(n - 1, n - 1), glm::dvec2(n - 1, n - 1));
    for (int k = 0; k < n; ++k) {
      EXPECT_EQ(at(0, k).x, 0.0);
      EXPECT_EQ(at(n - 1, k).x, n - 1.0);
      EXPECT_EQ(at(k, 0).y, 0.0);
      EXPECT_EQ(at(k, n - 1).y, n - 1.0);
    }
    expectNoFold(warped, n);
  }
}

TEST(GiwWarp, MovesSamplesTowardsImportance) {
  const int n = 33;
  // Importance ten times higher in the western half: more than half the columns go there.
  std::vector<float> importance(std::size_t(n) * std::size_t(n));
  for (int j = 0; j < n; ++j) {
    for (int i = 0; i < n; ++i) importance[std::size_t(j) * std::size_t(n) + std::size_t(i)] = i < n / 2 ? 10.0f : 1.0f;
  }
  const std::vector<glm::dvec2> warped = warpRowsThenColumns(importance, n, 0.0f);
  int west = 0;
  for (int i = 0; i < n; ++i) west += warped[std::size_t(n / 2) * std::size_t(n) + std::size_t(i)].x < (n - 1) / 2.0 ? 1 : 0;
  EXPECT_GT(west, 3 * n / 4);
  // Uniform importance leaves the grid where it was.
  std::fill(importance.begin(), importance.end(), 1.0f);
  const std::vector<glm::dvec2> even = warpRowsThenColumns(importance, n, 0.0f);
  for (int k = 0; k < n * n; ++k) {
    EXPECT_NEAR(even[std::size_t(k)].x, k % n, 1e-9);
    EXPECT_NEAR(even[std::size_t(k)].y, k / n, 1e-9);
  }
}

TEST(GiwWarp, TheViewsWarpOfRealisticTerrainDoesNotFold) {
  TerrainParams params;
  params.size = 257;
  params.spacingM = 30.0;
  params.erosion = 0.0;
  const HeightGrid grid = generateTerrain(params);
  Camera camera;
  camera.position = {2000.0, 1500.0, double(grid.heightAtWorld(2000.0, 1500.0)) + 400.0};
  camera.yawDeg = 40.0;
  camera.pitchDeg = -20.0;
  camera.fovYDeg = 50.0;
  const ViewSetup view = ViewSetup::create(camera, grid.worldBounds(), 640, 360);
  GiwSettings settings;
  settings.size = 65;
  const GeometryImage image = buildGeometryImage(grid, grid.heightRange().minM, view, 1.0f, settings);
  ASSERT_EQ(image.vertices.size(), 65u * 65u);
  // The region encloses the camera's ground position and lies on the grid.
  EXPECT_LE(image.region.min.x, camera.position.x / grid.spacingXM);
  EXPECT_GE(image.region.max.x, camera.position.x / grid.spacingXM);
  EXPECT_GE(image.region.min.x, 0.0);
  EXPECT_LE(image.region.max.y, grid.height - 1.0);
  std::vector<glm::dvec2> plan;
  for (const glm::vec3& v : image.vertices) plan.emplace_back(v.x, v.y);
  expectNoFold(plan, 65);
  EXPECT_FALSE(checkSettings(GiwSettings{3, 1.0f, 0.1f, 0.05f}));
  EXPECT_FALSE(checkSettings(GiwSettings{65, -1.0f, 0.1f, 0.05f}));
}

}  // namespace
}  // namespace tellus::giw
