#include <cmath>

#include <gtest/gtest.h>

#include "tellus/dem/terrain_generator.hpp"

namespace tellus {
namespace {

TerrainParams smallTerrain(std::uint64_t seed, double erosion = 1.0) {
  TerrainParams params;
  params.size = 257;
  params.seed = seed;
  params.spacingM = 60.0;
  params.erosion = erosion;
  return params;
}

TEST(TerrainGenerator, IsDeterministic) {
  const HeightGrid a = generateTerrain(smallTerrain(11));
  const HeightGrid b = generateTerrain(smallTerrain(11));
  EXPECT_EQ(a.heights, b.heights);
  EXPECT_EQ(a.width, 257);
  EXPECT_DOUBLE_EQ(a.spacingXM, 60.0);
}

TEST(TerrainGenerator, SeedsGiveDifferentTerrains) {
  const HeightGrid a = generateTerrain(smallTerrain(1));
  const HeightGrid b = generateTerrain(smallTerrain(2));
  size_t different = 0;
  for (size_t i = 0; i < a.heights.size(); ++i) different += a.heights[i] != b.heights[i];
  EXPECT_GT(different, a.heights.size() * 9 / 10);
}

TEST(TerrainGenerator, LooksLikeMountainsNotNoise) {
  const TerrainParams params = smallTerrain(7);
  const HeightGrid grid = generateTerrain(params);
  const HeightRange range = grid.heightRange();
  EXPECT_GE(range.minM, 0.0f);
  EXPECT_LE(range.maxM, float(params.reliefM * 1.6));
  EXPECT_GT(range.maxM - range.minM, float(params.reliefM * 0.3));  // real relief
  // Neighbouring samples are close (a continuous surface without cliffs or spikes): the
  // steepest step between neighbours stays below 70 degrees.
  float steepest = 0.0f;
  for (int row = 0; row < grid.height; ++row) {
    for (int col = 0; col + 1 < grid.width; ++col) {
      steepest = std::max(steepest, std::abs(grid.at(col + 1, row) - grid.at(col, row)));
    }
  }
  EXPECT_LT(steepest, float(params.spacingM * std::tan(70.0 * M_PI / 180.0)));
}

TEST(TerrainGenerator, ErosionReshapesTheSurface) {
  const HeightGrid raw = generateTerrain(smallTerrain(5, 0.0));
  const HeightGrid eroded = generateTerrain(smallTerrain(5, 1.0));
  double meanChange = 0.0;
  for (size_t i = 0; i < raw.heights.size(); ++i)
    meanChange += std::abs(raw.heights[i] - eroded.heights[i]);
  meanChange /= double(raw.heights.size());
  EXPECT_GT(meanChange, 1.0);    // metres: erosion did something
  EXPECT_LT(meanChange, 200.0);  // but did not destroy the terrain
}

}  // namespace
}  // namespace tellus
