// Editing material stacks (stacks/stack_edit.hpp): intervals filled or emptied in a column, a
// sphere carving a cave and adding a boulder, the pyramid above re-aggregated only where the
// edit reached (the same as aggregating the edited terrain anew), bad edits refused.
#include <gtest/gtest.h>

#include <algorithm>
#include <random>

#include "tellus/formats/stacks/column_splice.hpp"
#include "tellus/formats/stacks/stack_aggregation.hpp"
#include "tellus/formats/stacks/stack_edit.hpp"

namespace tellus {
namespace {

constexpr StackMaterial kRock = 1, kSoil = 2;

StackTerrain block(int w, int h, float topM) {
  std::vector<std::vector<StackLayer>> columns(std::size_t(w) * std::size_t(h),
                                               {{0.0f, topM - 1.0f, kRock}, {topM - 1.0f, topM, kSoil}});
  return StackTerrain::fromColumns(w, h, 2.0, columns).value();
}

TEST(StackEdit, FillIntervalSplitsAndMergesLayers) {
  const std::vector<StackLayer> column{{0, 10, kRock}, {10, 12, kSoil}};
  // A cave in the rock: the rock splits around the air.
  EXPECT_EQ(fillInterval(column, 4, 6, kAir),
            (std::vector<StackLayer>{{0, 4, kRock}, {6, 10, kRock}, {10, 12, kSoil}}));
  // Rock over the soil and above: the soil's top part and the air become rock, one layer.
  EXPECT_EQ(fillInterval(column, 11, 15, kRock),
            (std::vector<StackLayer>{{0, 10, kRock}, {10, 11, kSoil}, {11, 15, kRock}}));
  // Floating rock in the air above, and rock filling rock: nothing merges across the gap.
  EXPECT_EQ(fillInterval(column, 20, 21, kRock),
            (std::vector<StackLayer>{{0, 10, kRock}, {10, 12, kSoil}, {20, 21, kRock}}));
  EXPECT_EQ(fillInterval(column, 2, 3, kRock), column);
  EXPECT_EQ(fillInterval(column, 0, 30, kAir), std::vector<StackLayer>{});
  EXPECT_TRUE(checkStackColumn(fillInterval(column, 9, 11, kAir)));
}

TEST(StackEdit, SphereCarvesOnlyItsDiscAndThePyramidFollows) {
  StackTerrain terrain = block(32, 24, 20.0f);
  std::vector<StackTerrain> pyramid = buildStackPyramid(terrain);
  SphereEdit cave{20.0, 14.0, 10.0, 5.0, kAir};
  Result<StackRegion> region = applySphereEdit(pyramid.front(), cave);
  ASSERT_TRUE(region) << region.error().message;
  ASSERT_FALSE(region->empty());
  // Columns 8..12 (x 16..24 m) and sample rows 5..9 north, i.e. terrain rows 14..18.
  EXPECT_EQ(region->x0, 8);
  EXPECT_EQ(region->x1, 12);
  EXPECT_EQ(region->y0, 14);
  EXPECT_EQ(region->y1, 18);
  // The centre column has air from 5 to 15 m; a column outside the disc is unchanged.
  const auto centre = pyramid.front().column(10, 24 - 1 - 7);
  ASSERT_EQ(centre.size(), 3u);
  EXPECT_EQ(centre[0], (StackLayer{0, 5, kRock}));
  EXPECT_EQ(centre[1], (StackLayer{15, 19, kRock}));
  EXPECT_EQ(pyramid.front().column(0, 0).size(), 2u);
  // The levels above are what aggregating the edited terrain anew gives.
  const std::vector<StackRegion> changed = updatePyramid(pyramid, region.value());
  ASSERT_EQ(changed.size(), pyramid.size());
  const std::vector<StackTerrain> fresh = buildStackPyramid(pyramid.front());
  for (std::size_t k = 1; k < pyramid.size(); ++k) {
    ASSERT_EQ(pyramid[k].layers(), fresh[k].layers()) << "level " << k;
    ASSERT_EQ(pyramid[k].offsets(), fresh[k].offsets()) << "level " << k;
  }
  // Adding a boulder on top.
  Result<StackRegion> boulder = applySphereEdit(pyramid.front(), {40.0, 20.0, 22.0, 3.0, kRock});
  ASSERT_TRUE(boulder);
  EXPECT_GT(pyramid.front().topM(), 24.0f);
}

// Splicing runs of columns in place equals rebuilding the arrays, whether the runs grow,
// shrink or mix both (blocks moving left and right in one splice).
TEST(StackEdit, SplicedColumnsEqualARebuild) {
  std::mt19937 random(7);
  for (int trial = 0; trial < 200; ++trial) {
    const std::size_t columns = 1 + random() % 40;
    std::vector<std::vector<int>> expected(columns);
    int next = 0;
    for (auto& column : expected) column.resize(random() % 4, 0), std::generate(column.begin(), column.end(), [&] { return next++; });
    std::vector<int> layers;
    std::vector<std::uint32_t> offsets{0};
    for (const auto& column : expected) {
      layers.insert(layers.end(), column.begin(), column.end());
      offsets.push_back(std::uint32_t(layers.size()));
    }
    std::vector<ColumnRun<int>> runs;
    for (std::size_t c = random() % 3; c < columns; c += 1 + random() % 5) {
      ColumnRun<int>& run = runs.emplace_back();
      run.firstColumn = c;
      const std::size_t count = std::min<std::size_t>(1 + random() % 3, columns - c);
      for (std::size_t i = 0; i < count; ++i) {
        std::vector<int> column(random() % 6, 0);
        for (int& layer : column) layer = -(next++);
        run.counts.push_back(std::uint32_t(column.size()));
        run.layers.insert(run.layers.end(), column.begin(), column.end());
        expected[c + i] = column;
      }
      c += count;
    }
    spliceColumns(layers, offsets, runs);
    std::vector<int> rebuilt;
    std::vector<std::uint32_t> rebuiltOffsets{0};
    for (const auto& column : expected) {
      rebuilt.insert(rebuilt.end(), column.begin(), column.end());
      rebuiltOffsets.push_back(std::uint32_t(rebuilt.size()));
    }
    ASSERT_EQ(layers, rebuilt) << "trial " << trial;
    ASSERT_EQ(offsets, rebuiltOffsets) << "trial " << trial;
  }
}

TEST(StackEdit, RayFindsTheFirstSolidPoint) {
  const StackTerrain terrain = block(16, 16, 10.0f);
  const auto hit = firstSolidAlongRay(terrain, {10.0, 10.0, 50.0}, {0.0, 0.0, -1.0}, 100.0);
  ASSERT_TRUE(hit);
  EXPECT_NEAR(hit->z, 10.0, 0.01);
  EXPECT_FALSE(firstSolidAlongRay(terrain, {10.0, 10.0, 50.0}, {0.0, 0.0, 1.0}, 100.0));
  EXPECT_FALSE(firstSolidAlongRay(terrain, {10.0, 10.0, 50.0}, {0.0, 0.0, -1.0}, 20.0));  // too far
}

TEST(StackEdit, BadEditsAreRefused) {
  StackTerrain terrain = block(8, 8, 10.0f);
  EXPECT_FALSE(applySphereEdit(terrain, {4, 4, 5, 0, kAir}));        // no radius
  EXPECT_FALSE(applySphereEdit(terrain, {4, 4, 5, -1, kAir}));
  EXPECT_FALSE(applySphereEdit(terrain, {1e9, 4, 5, 3, kAir}));      // off the terrain
  EXPECT_FALSE(applySphereEdit(terrain, {4, 4, -10, 3, kAir}));      // under the base
  EXPECT_FALSE(applySphereEdit(terrain, {std::nan(""), 4, 5, 3, kAir}));
  // Nothing to change: an empty region.
  Result<StackRegion> none = applySphereEdit(terrain, {4, 4, 50, 2, kAir});
  ASSERT_TRUE(none);
  EXPECT_TRUE(none->empty());
}

}  // namespace
}  // namespace tellus
