// The rings structure: levels by distance, the toroidal incremental update against a fresh
// rebuild after random walks, and the stitching look-up against the real neighbour levels.
#include <random>

#include <gtest/gtest.h>

#include "tellus/lod/rings/rings_structure.hpp"

namespace tellus {
namespace {

TEST(RingsStructure, LevelsDoubleWithDistance) {
  const std::vector<int> expected = {0, 0, 1, 1, 2, 2, 2, 2, 3, 3, 3, 3, 3, 3, 3, 3, 4};
  for (int d = 0; d < int(expected.size()); ++d) {
    EXPECT_EQ(RingsStructure::levelAtDistance(d, 10), expected[std::size_t(d)]) << d;
  }
  EXPECT_EQ(RingsStructure::levelAtDistance(1000, 3), 3);  // capped
}

TEST(RingsStructure, IncrementalUpdatesEqualAFreshRebuildAfterAnyWalk) {
  Result<RingsStructure> rings = RingsStructure::create(3, 8, 40, 30, 5, 5);
  ASSERT_TRUE(rings);
  EXPECT_EQ(rings->reach(), 7);
  EXPECT_EQ(rings->side(), 15);
  std::mt19937 random(42);
  std::uniform_int_distribution<int> step(-1, 1);
  for (int move = 0; move < 400; ++move) {
    const int dx = step(random), dy = step(random);
    const int x = rings->centreX() + dx, y = rings->centreY() + dy;
    Result<int> refilled = rings->updateRings(x, y);
    ASSERT_TRUE(refilled);
    // Only the entering row and/or column were refilled.
    EXPECT_EQ(refilled.value(), (dx != 0 ? 15 : 0) + (dy != 0 ? 15 : 0));
    Result<RingsStructure> fresh = RingsStructure::create(3, 8, 40, 30, x, y);
    ASSERT_TRUE(fresh);
    for (int sy = 0; sy < rings->side(); ++sy) {
      for (int sx = 0; sx < rings->side(); ++sx) {
        const RingPatch a = rings->slot(sx, sy), b = fresh->slot(sx, sy);
        ASSERT_EQ(a.x, b.x) << "move " << move << " slot " << sx << "," << sy;
        ASSERT_EQ(a.y, b.y) << "move " << move << " slot " << sx << "," << sy;
        ASSERT_EQ(a.level, b.level);
        ASSERT_EQ(a.orientation, b.orientation);
        ASSERT_EQ(a.stitchEdges, b.stitchEdges);
      }
    }
    for (int oy = -7; oy <= 7; ++oy)
      for (int ox = -7; ox <= 7; ++ox) {
        const RingPatch p = rings->patchAt(ox, oy);
        ASSERT_EQ(p.x, x + ox);
        ASSERT_EQ(p.y, y + oy);
      }
  }
  EXPECT_FALSE(rings->updateRings(rings->centreX() + 2, rings->centreY()));
}

TEST(RingsStructure, OrientationsFollowTheSeedsTable) {
  Result<RingsStructure> rings = RingsStructure::create(3, 8, 100, 100, 50, 50);
  ASSERT_TRUE(rings);
  struct Case {
    int dx, dy;
    PatchOrientation orientation;
    std::uint8_t outward;
  };
  const std::vector<Case> cases = {
      {0, 0, PatchOrientation::Centre, 0},
      {0, -3, PatchOrientation::North, kEdgeUp},
      {3, -3, PatchOrientation::NorthEast, kEdgeUp | kEdgeRight},
      {3, 1, PatchOrientation::East, kEdgeRight},
      {3, 3, PatchOrientation::SouthEast, kEdgeRight | kEdgeDown},
      {-2, 3, PatchOrientation::South, kEdgeDown},
      {-3, 3, PatchOrientation::SouthWest, kEdgeDown | kEdgeLeft},
      {-3, 0, PatchOrientation::West, kEdgeLeft},
      {-3, -3, PatchOrientation::NorthWest, kEdgeLeft | kEdgeUp},
  };
  for (const Case& c : cases) {
    const RingPatch p = rings->patchAt(c.dx, c.dy);
    EXPECT_EQ(p.orientation, c.orientation) << c.dx << "," << c.dy;
    EXPECT_EQ(outwardEdges(p.orientation), c.outward) << c.dx << "," << c.dy;
    // Distance 3 is the outer edge of ring 1 (level 1): its outward edges meet level 2.
    if (p.distance == 3) {
      EXPECT_EQ(p.stitchEdges, c.outward);
    }
  }
  EXPECT_EQ(rings->patchAt(0, -2).stitchEdges, 0);  // distance 2 and 3 share level 1
  EXPECT_EQ(rings->patchAt(1, 1).stitchEdges, kEdgeRight | kEdgeDown);  // level 0 meets level 1
}

// The property the GPU stitching needs, for every patch and every edge: neighbours differ by at
// most one level, and exactly the finer side of a level change stitches the shared edge.
TEST(RingsStructure, StitchEdgesMatchTheNeighbourLevelsEverywhere) {
  for (const auto& [maxLevel, viewerHeight] :
       std::vector<std::pair<int, int>>{{1, 0}, {2, 0}, {8, 0}, {8, 3}, {8, 6}, {2, 5}, {8, 40}}) {
    Result<RingsStructure> rings = RingsStructure::create(4, maxLevel, 200, 200, 90, 90);
    ASSERT_TRUE(rings);
    rings->setViewerHeight(viewerHeight);
    const int reach = rings->reach();
    const std::array<std::pair<std::uint8_t, std::pair<int, int>>, 4> edges = {
        {{kEdgeUp, {0, -1}}, {kEdgeRight, {1, 0}}, {kEdgeDown, {0, 1}}, {kEdgeLeft, {-1, 0}}}};
    for (int dy = -reach + 1; dy < reach; ++dy) {
      for (int dx = -reach + 1; dx < reach; ++dx) {
        const RingPatch p = rings->patchAt(dx, dy);
        for (const auto& [edge, offset] : edges) {
          const RingPatch n = rings->patchAt(dx + offset.first, dy + offset.second);
          ASSERT_LE(std::abs(n.level - p.level), 1) << dx << "," << dy;
          const bool stitched = (p.stitchEdges & edge) != 0;
          ASSERT_EQ(stitched, n.level > p.level)
              << "patch " << dx << "," << dy << " edge " << int(edge) << " maxLevel " << maxLevel
              << " viewer height " << viewerHeight;
          ASSERT_EQ(p.level, rings->levelOf(p.x, p.y));
        }
      }
    }
  }
}

// A viewer high above the ground sees the patches beneath it as far away: no full detail
// under a plane at 30 patch widths, and the levels still grow outwards.
TEST(RingsStructure, AHighViewerCoarsensTheGroundBeneathIt) {
  Result<RingsStructure> rings = RingsStructure::create(6, 8, 100, 100, 50, 50);
  ASSERT_TRUE(rings);
  EXPECT_EQ(rings->patchAt(0, 0).level, 0);
  rings->setViewerHeight(30);
  EXPECT_EQ(rings->patchAt(0, 0).level, 4);  // as if 30 patches away
  EXPECT_EQ(rings->patchAt(29, 0).level, 4);
  EXPECT_EQ(rings->patchAt(32, 0).level, 5);  // beyond the height, distance rules again
  EXPECT_EQ(rings->patchAt(0, 0).stitchEdges, 0);
  EXPECT_EQ(rings->patchAt(31, 0).stitchEdges, kEdgeRight);
  rings->setViewerHeight(-5);  // below ground counts as on it
  EXPECT_EQ(rings->viewerHeight(), 0);
}

TEST(RingsStructure, ActivePatchesStayInsideTheTerrain) {
  Result<RingsStructure> rings = RingsStructure::create(2, 8, 4, 3, 0, 0);
  ASSERT_TRUE(rings);
  const std::vector<RingPatch> patches = rings->activePatches();
  EXPECT_EQ(patches.size(), 4u * 3u);  // reach 3 covers the whole 4x3 grid from its corner
  for (const RingPatch& p : patches) EXPECT_TRUE(p.inside);
  EXPECT_FALSE(RingsStructure::create(0, 8, 4, 3, 0, 0));
  EXPECT_FALSE(RingsStructure::create(2, 8, 0, 3, 0, 0));
}

}  // namespace
}  // namespace tellus
