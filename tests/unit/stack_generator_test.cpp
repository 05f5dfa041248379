// Material stacks from heightfields (stack_generator.hpp): the ground's layers, and each 3D
// feature appearing where it should, never floating, the same for a seed.
#include <gtest/gtest.h>

#include "tellus/formats/stacks/stack_generator.hpp"

namespace tellus {
namespace {

HeightGrid gridOf(int w, int h, double spacing, const std::function<float(int, int)>& height) {
  HeightGrid g(w, h);
  g.spacingXM = g.spacingYM = spacing;
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) g.at(x, y) = height(x, y);
  }
  return g;
}

StackGeneratorOptions only(bool caves, bool overhangs, bool arches) {
  StackGeneratorOptions o;
  o.features = {caves, overhangs, arches};
  return o;
}

// Columns with air between solid layers (a gap), and whether any layer floats.
int columnsWithGaps(const StackTerrain& t) {
  int n = 0;
  for (int y = 0; y < t.height(); ++y) {
    for (int x = 0; x < t.width(); ++x) {
      const auto c = t.column(x, y);
      for (std::size_t i = 1; i < c.size(); ++i) {
        if (c[i].bottomM > c[i - 1].topM) {
          ++n;
          break;
        }
      }
    }
  }
  return n;
}

std::size_t floating(const StackTerrain& t) {
  std::vector<std::vector<StackLayer>> columns;
  for (int y = 0; y < t.height(); ++y) {
    for (int x = 0; x < t.width(); ++x) {
      const auto c = t.column(x, y);
      columns.emplace_back(c.begin(), c.end());
    }
  }
  return removeFloatingLayers(t.width(), t.height(), columns);
}

TEST(StackGenerator, TheGroundIsRockSoilAndGrassThinningOnSlopes) {
  // Flat at 100 m on the left, a 60-degree slope on the right.
  const HeightGrid grid = gridOf(16, 4, 2.0, [](int x, int) {
    return x < 8 ? 100.0f : 100.0f + float(x - 7) * 3.5f;
  });
  Result<StackTerrain> t = generateStacks(grid, only(false, false, false));
  ASSERT_TRUE(t) << t.error().message;
  const auto flat = t->column(2, 1);
  ASSERT_EQ(flat.size(), 3u);
  EXPECT_EQ(flat[0], (StackLayer{0.0f, 6.5f, kStackRock}));  // base 92 m: ground 8 m up
  EXPECT_EQ(flat[1].material, kStackSoil);
  EXPECT_EQ(flat[2], (StackLayer{7.75f, 8.0f, kStackGrass}));
  const auto steep = t->column(12, 1);
  ASSERT_EQ(steep.size(), 1u);  // bare rock
  EXPECT_EQ(steep[0].material, kStackRock);
  EXPECT_FLOAT_EQ(steep[0].topM, 8.0f + 5 * 3.5f);
  EXPECT_EQ(columnsWithGaps(t.value()), 0);
}

TEST(StackGenerator, CliffsGetOverhangingLipsJoinedToThem) {
  // A 40 m cliff across the middle, 2 m stacks.
  const HeightGrid grid = gridOf(32, 64, 2.0, [](int x, int) { return x < 16 ? 140.0f : 100.0f; });
  Result<StackTerrain> t = generateStacks(grid, only(false, true, false));
  ASSERT_TRUE(t);
  const int lips = columnsWithGaps(t.value());
  RecordProperty("columns_with_lips", lips);
  EXPECT_GT(lips, 3);
  EXPECT_EQ(floating(t.value()), 0u);
  // Lips hang over the low side only, next to the cliff.
  for (int y = 0; y < 64; ++y) {
    EXPECT_EQ(t->column(4, y).size(), t->column(5, y).size());
    EXPECT_LE(t->column(25, y).size(), 3u);
  }
}

TEST(StackGenerator, AValleyGetsAnArchOverAGap) {
  // A V valley 90 m deep between two ridges.
  const HeightGrid grid = gridOf(64, 48, 2.0, [](int x, int) { return 100.0f + 3.0f * float(std::abs(x - 32)); });
  Result<StackTerrain> t = generateStacks(grid, only(false, false, true));
  ASSERT_TRUE(t);
  int spans = 0;
  for (int y = 0; y < 48; ++y) spans += t->column(32, y).size() > 3 ? 1 : 0;  // ground + deck
  RecordProperty("arch_rows", spans);
  EXPECT_GT(spans, 0);
  EXPECT_EQ(floating(t.value()), 0u);
}

TEST(StackGenerator, CavesRunUnderTheGroundAndOpenAtItsSurface) {
  const HeightGrid grid = gridOf(96, 96, 2.0, [](int x, int y) {
    return 100.0f + 10.0f * std::sin(float(x) * 0.1f) * std::cos(float(y) * 0.07f);
  });
  Result<StackTerrain> t = generateStacks(grid, only(true, false, false));
  ASSERT_TRUE(t);
  const int gaps = columnsWithGaps(t.value());
  RecordProperty("columns_with_caves", gaps);
  EXPECT_GT(gaps, 50);  // tunnels under the ground
  EXPECT_LT(gaps, 96 * 96 / 2);  // not a sponge
  int mouths = 0;  // columns whose top lies below the DEM's ground: the surface opened
  const float base = 90.0f - 8.0f - 40.0f;
  for (int y = 0; y < 96; ++y) {
    for (int x = 0; x < 96; ++x) {
      const auto c = t->column(x, y);
      if (c.empty() || c.back().topM < grid.at(x, y) - base - 1.0f) ++mouths;
    }
  }
  RecordProperty("cave_mouths", mouths);
  EXPECT_GT(mouths, 0);
  EXPECT_EQ(floating(t.value()), 0u);
  // Deterministic: the same seed, the same stacks; another seed, others.
  Result<StackTerrain> again = generateStacks(grid, only(true, false, false));
  EXPECT_EQ(again->layers(), t->layers());
  StackGeneratorOptions other = only(true, false, false);
  other.seed = 8;
  EXPECT_NE(generateStacks(grid, other)->layers(), t->layers());
}

TEST(StackGenerator, FloatingRockIsRemovedAndJoinedRockKept) {
  std::vector<std::vector<StackLayer>> columns = {
      {{0, 10, kStackRock}},
      {{0, 10, kStackRock}, {20, 25, kStackRock}},  // touches nothing: floating
      {{0, 10, kStackRock}}};
  EXPECT_EQ(removeFloatingLayers(3, 1, columns), 1u);
  EXPECT_EQ(columns[1].size(), 1u);
  columns = {{{0, 10, kStackRock}},
             {{0, 10, kStackRock}, {20, 25, kStackRock}},
             {{0, 30, kStackRock}}};  // the block leans on this column's cliff: joined
  EXPECT_EQ(removeFloatingLayers(3, 1, columns), 0u);
  EXPECT_FALSE(generateStacks(HeightGrid(1, 1), {}));
  HeightGrid stretched = gridOf(4, 4, 2.0, [](int, int) { return 0.0f; });
  stretched.spacingYM = 3.0;
  Result<StackTerrain> refused = generateStacks(stretched, {});
  ASSERT_FALSE(refused);
  EXPECT_NE(refused.error().message.find("square cells"), std::string::npos);
}

}  // namespace
}  // namespace tellus
