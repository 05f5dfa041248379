// RINGO's blocks (seed 002): the ring layout and its 4x triangle ratio (the seed's 11 x 11
// matrix), the depth chosen from the viewer's height, and the toroidal matrix: after any
// sequence of moves it equals a matrix built where it ended, only the slots that change are
// rebuilt, coarser blocks derive from their own finer samples and the antimeridian is an
// ordinary step.
#include <gtest/gtest.h>

#include <limits>
#include <vector>

#include <map>
#include <random>

#include "tellus/lod/ringo/ringo_block_matrix.hpp"
#include "tellus/lod/ringo/ringo_layout.hpp"

namespace tellus {
namespace {

TEST(RingoLayout, RingsOfFourTimesFewerTriangles) {
  const RingoLayout layout;  // 4 rings: the seed's 11 x 11
  EXPECT_EQ(layout.side(), 11);
  EXPECT_EQ(RingoLayout::levelAt(0, 0), 0);
  EXPECT_EQ(RingoLayout::levelAt(1, -1), 0);  // the central 3 x 3
  EXPECT_EQ(RingoLayout::levelAt(2, 0), 1);
  EXPECT_EQ(RingoLayout::levelAt(-3, 2), 2);
  EXPECT_EQ(RingoLayout::levelAt(5, -5), 4);
  for (int level = 1; level <= 4; ++level) {
    EXPECT_EQ(layout.trianglesAt(level - 1), 4 * layout.trianglesAt(level)) << level;
  }
  // Blocks per level: 9 central, then 16, 24, 32, 40 in the rings.
  std::map<int, int> blocks;
  for (int dy = -5; dy <= 5; ++dy) {
    for (int dx = -5; dx <= 5; ++dx) ++blocks[RingoLayout::levelAt(dx, dy)];
  }
  EXPECT_EQ(blocks, (std::map<int, int>{{0, 9}, {1, 16}, {2, 24}, {3, 32}, {4, 40}}));
  // The seed's 1,746,000 triangles are 240-cell blocks; Tellus's blocks are the store's
  // 256-cell tiles.
  EXPECT_EQ((RingoLayout{.rings = 4, .tileCells = 240}.totalTriangles()), 1'746'000u);
  EXPECT_EQ(layout.totalTriangles(), 1'986'560u);
}

TEST(RingoLayout, DepthFollowsTheHeightAboveTheGround) {
  const RingoLayout layout;
  EXPECT_EQ(minimumRingoDepth(layout), 3);  // 16 tiles round the globe hold 11
  int previous = 100;
  for (const double clearance : {1.0, 2.0, 100.0, 500.0, 5e3, 5e4, 5e5, 5e6, 2e7}) {
    const int depth = ringoDepthFor(clearance, 29, layout);
    EXPECT_LE(depth, previous) << clearance;
    previous = depth;
  }
  EXPECT_EQ(ringoDepthFor(2e7, 29, layout), 3);  // from orbit: the shallowest that fits
  EXPECT_EQ(ringoDepthFor(2.0, 10, layout), 10);  // near the ground: no deeper than the store
  // 500 m up the horizon is 80 km: blocks of about 16 km, depth 10 (19.5 km at the equator).
  EXPECT_EQ(ringoDepthFor(500.0, 29, layout), 10);
  // Hysteresis: 2,000 m (ideal 9.3) keeps a matrix at depth 10, 4,000 m (ideal 8.8) does not.
  EXPECT_EQ(ringoDepthFor(1000.0, 29, layout), 10);
  EXPECT_EQ(ringoDepthFor(2000.0, 29, layout), 9);
  EXPECT_EQ(ringoDepthFor(2000.0, 29, layout, 10), 10);
  EXPECT_EQ(ringoDepthFor(4000.0, 29, layout, 10), 9);
  EXPECT_EQ(ringoDepthFor(1500.0, 29, layout, 9), 9);
  // Deeper as soon as the ideal rounds deeper (1,300 m: ideal 9.6), coarser only 0.75 below.
  EXPECT_EQ(ringoDepthFor(1300.0, 29, layout, 9), 10);
  EXPECT_EQ(ringoDepthFor(1300.0, 29, layout, 10), 10);
  EXPECT_EQ(ringoDepthFor(100.0, 29, layout, 9), 11);
  // The block size: twice as many blocks to the horizon, blocks half as wide, one depth deeper.
  EXPECT_EQ(ringoDepthFor(500.0, 29, layout, -1, 2.0 * kRingoBlocksToHorizon), 11);
  EXPECT_EQ(ringoDepthFor(500.0, 29, layout, -1, 0.5 * kRingoBlocksToHorizon), 9);
}

// A flight centres its matrices where it will be when they are drawn; the first frame, a
// hover and a jump across the globe centre them where the viewer is.
TEST(RingoLayout, AFlightCentresItsMatricesWhereItWillBe) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const auto planned = [](RingoLatLon now, RingoLatLon last, int frames) {
    return ringoPlannedPosition(now, last, frames);
  };
  RingoLatLon p = planned({46.4, 13.8}, {nan, nan}, 2);
  EXPECT_EQ(p.latDeg, 46.4);
  EXPECT_EQ(p.lonDeg, 13.8);
  p = planned({46.4, 13.8}, {46.4, 13.8}, 2);  // hovering
  EXPECT_EQ(p.latDeg, 46.4);
  EXPECT_EQ(p.lonDeg, 13.8);
  p = planned({46.44, 13.85}, {46.41, 13.81}, 2);  // the steep low flight: 4 km a frame
  EXPECT_NEAR(p.latDeg, 46.50, 1e-9);
  EXPECT_NEAR(p.lonDeg, 13.93, 1e-9);
  p = planned({10.0, 179.9}, {10.0, 179.7}, 2);  // across the antimeridian
  EXPECT_NEAR(p.lonDeg, -179.7, 1e-9);
  p = planned({89.9, 0.0}, {89.5, 0.0}, 2);  // not beyond a pole
  EXPECT_EQ(p.latDeg, 90.0);
  p = planned({36.0, 128.0}, {46.0, 14.0}, 2);  // a jump: no extrapolation
  EXPECT_EQ(p.latDeg, 36.0);
  EXPECT_EQ(p.lonDeg, 128.0);
}

// A descent plans its matrices for the clearance it will have when they are drawn; climbing,
// hovering and the first frame plan for the clearance now.
TEST(RingoLayout, ADescentPlansForTheClearanceAhead) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  EXPECT_EQ(ringoPlannedClearance(1000.0, nan, 2), 1000.0);
  EXPECT_EQ(ringoPlannedClearance(1000.0, 800.0, 2), 1000.0);    // climbing
  EXPECT_EQ(ringoPlannedClearance(1000.0, 1000.0, 2), 1000.0);   // hovering
  EXPECT_DOUBLE_EQ(ringoPlannedClearance(1000.0, 2000.0, 2), 250.0);  // halving a frame
  EXPECT_DOUBLE_EQ(ringoPlannedClearance(1000.0, 1e6, 2), 1000.0 / 16.0);  // at most 4x a frame
  EXPECT_DOUBLE_EQ(ringoPlannedClearance(1000.0, 2000.0, 0), 1000.0);
  // The descent at the end of the descent path (two thirds of the height a frame): the planned
  // matrix is a depth finer than the one for the clearance now.
  const RingoLayout layout;
  EXPECT_EQ(ringoDepthFor(ringoPlannedClearance(3000.0, 4500.0, kRingoMatrixLatencyFrames), 29,
                          layout),
            ringoDepthFor(3000.0, 29, layout) + 1);
}

// A flight over ridges plans only the descent it makes: the ground rising hundreds of metres a
// frame under a level flight is not a descent, nor is a terrain-following flight's drop down a
// slope (its clearance stays). The ground is the steep low flight's (the generated range, every
// frame's ground under the viewer, metres). Extrapolating the clearance's own change, as before,
// flipped a level flight's depth back and forth on it.
TEST(RingoLayout, AFlightOverRidgesPlansOnlyItsOwnDescent) {
  const std::vector<double> groundM = {
      -1,   6,    20,   66,   140,  248,  319,  377,  447,  514,  594,  1039, 1341, 1182,
      955,  953,  1330, 2203, 2676, 1513, 1249, 1558, 680,  529,  1221, 1409, 710,  465,
      679,  1059, 1481, 1380, 1177, 958,  1112, 1335, 1271, 1125, 982,  947,  927,  923};
  const RingoLayout layout;
  const double nan = std::numeric_limits<double>::quiet_NaN();
  // Depths chosen frame by frame (with the hysteresis) for the clearance `planFor(i)`.
  const auto depths = [&](const auto& planFor) {
    std::vector<int> chosen;
    int depth = -1;
    for (std::size_t i = 0; i < groundM.size(); ++i) {
      depth = ringoDepthFor(planFor(i), 29, layout, depth);
      chosen.push_back(depth);
    }
    return chosen;
  };
  const auto changes = [](const std::vector<int>& d) {
    int n = 0;
    for (std::size_t i = 1; i < d.size(); ++i) n += d[i] != d[i - 1] ? 1 : 0;
    return n;
  };
  const auto inFlight = [&](const auto& eyeAt) {
    return depths([&](std::size_t i) {
      return ringoPlannedClearanceInFlight(eyeAt(i), i ? eyeAt(i - 1) : nan, groundM[i],
                                           i ? groundM[i - 1] : nan, kRingoMatrixLatencyFrames);
    });
  };
  // Level, 3,500 m up: the depths are those of the clearance now, down over the highest ridge
  // and back.
  const auto level = [](std::size_t) { return 3500.0; };
  const std::vector<int> planned = inFlight(level);
  EXPECT_EQ(planned, depths([&](std::size_t i) { return 3500.0 - groundM[i]; }));
  EXPECT_LE(changes(planned), 2);
  const std::vector<int> extrapolated = depths([&](std::size_t i) {
    return ringoPlannedClearance(3500.0 - groundM[i], i ? 3500.0 - groundM[i - 1] : nan,
                                 kRingoMatrixLatencyFrames);
  });
  EXPECT_GE(changes(extrapolated), 2 * changes(planned) + 2);
  // Following the ground 500 m above it: one depth all along.
  EXPECT_EQ(changes(inFlight([&](std::size_t i) { return groundM[i] + 500.0; })), 0);
  // A vertical descent over high ground is still planned ahead: 4,500 m then 3,000 m above
  // ground 1,000 m up plans as 3,000 m then 2,000 m above flat ground at sea level.
  EXPECT_DOUBLE_EQ(ringoPlannedClearanceInFlight(4000.0, 5500.0, 1000.0, 1000.0, 2),
                   ringoPlannedClearance(3000.0, 4500.0, 2));
  // Descending towards rising ground: the smaller of the two descents (the height's, 1,500 m).
  EXPECT_DOUBLE_EQ(ringoPlannedClearanceInFlight(4000.0, 5500.0, 1000.0, 500.0, 2),
                   ringoPlannedClearance(3000.0, 4500.0, 2));
  EXPECT_EQ(ringoPlannedClearanceInFlight(4000.0, 3500.0, 1000.0, 1000.0, 2), 3000.0);  // climbing
  EXPECT_EQ(ringoPlannedClearanceInFlight(4000.0, nan, 1000.0, nan, 2), 3000.0);  // first frame
}

// The slots' contents as a renderer would keep them, replayed from the updates.
struct Contents {
  std::vector<RingoBlock> blocks;
  void apply(const std::vector<RingoBlockUpdate>& updates) {
    for (const RingoBlockUpdate& u : updates) {
      RingoBlock& held = blocks[std::size_t(u.slot)];
      if (u.source == RingoBlockSource::Derived) {
        // Derived from the slot's own block, finer: same tile, more cells.
        ASSERT_TRUE(held.exists);
        ASSERT_EQ(held.key, u.block.key);
        ASSERT_LT(held.level, u.block.level);
        ASSERT_EQ(held.level, u.previousLevel);
      }
      if (u.source == RingoBlockSource::Removed) {
        ASSERT_FALSE(u.block.exists);
      }
      held = u.block;
    }
  }
};

TEST(RingoBlockMatrix, AnySequenceOfMovesEqualsAFreshMatrix) {
  const RingoLayout layout;
  const int depth = 6;  // 128 x 64 tiles: poles and the antimeridian within reach
  std::mt19937 random(7);
  std::uniform_int_distribution<int> step(-1, 1), jump(-9, 9);
  RingoBlockMatrix matrix(layout, depth, 120, 30);
  Contents contents;
  for (int i = 0; i < matrix.slotCount(); ++i) contents.blocks.push_back(matrix.slot(i));
  std::int64_t x = 120;
  int y = 30;
  for (int move = 0; move < 600; ++move) {
    const bool far = move % 50 == 49;
    x += far ? jump(random) : step(random);
    y = std::clamp(y + (far ? jump(random) : step(random)), -3, GlobalTiling::tilesY(depth) + 2);
    contents.apply(matrix.recentre(x, y));
    const RingoBlockMatrix fresh(layout, depth, x, y);
    for (int i = 0; i < matrix.slotCount(); ++i) {
      ASSERT_EQ(matrix.slot(i), fresh.slot(i)) << "move " << move << " slot " << i;
      ASSERT_EQ(contents.blocks[std::size_t(i)], fresh.slot(i)) << "move " << move;
    }
  }
}

TEST(RingoBlockMatrix, OneStepNorthRebuildsOnlyTheChangedSlotsInColumnLanes) {
  const RingoLayout layout;
  RingoBlockMatrix matrix(layout, 10, 1000, 300);
  const std::vector<RingoBlockUpdate> updates = matrix.recentre(1000, 299);  // one row north
  int entered = 0, finer = 0, derived = 0;
  for (const RingoBlockUpdate& u : updates) {
    EXPECT_EQ(u.lane, u.slot % layout.side());  // a move north: one lane per column
    EXPECT_TRUE(u.block.exists);
    if (u.source == RingoBlockSource::Derived) {
      ++derived;
      EXPECT_EQ(u.block.level, u.previousLevel + 1);
    } else if (u.block.key.y == 299 - 5) {
      ++entered;  // the new northern row
    } else {
      ++finer;  // R blocks: the same tiles, one level finer
      EXPECT_EQ(u.block.level, u.previousLevel - 1);
    }
  }
  EXPECT_EQ(entered, 11);
  // Each ring's northern half gains detail and its southern half loses it: the seed's R and D.
  EXPECT_EQ(finer, derived);
  EXPECT_GT(derived, 0);
  // Blocks whose level does not change stay where they are: fewer than half the slots change.
  EXPECT_LT(updates.size(), std::size_t(matrix.slotCount()) / 2);
}

TEST(RingoBlockMatrix, TheAntimeridianIsAnOrdinaryStepAndPolesHoldNothing) {
  const RingoLayout layout;
  const int depth = 5;
  const int columns = GlobalTiling::tilesX(depth);
  RingoBlockMatrix west(layout, depth, columns - 1, 10);
  RingoBlockMatrix reference(layout, depth, 40, 10);
  const std::size_t acrossSeam = west.recentre(columns, 10).size();
  const std::size_t elsewhere = reference.recentre(41, 10).size();
  EXPECT_EQ(acrossSeam, elsewhere);
  EXPECT_EQ(west.at(0, 0).key.x, 0);  // column `columns` is tile column 0
  EXPECT_EQ(west.at(-1, 0).key.x, columns - 1);
  RingoBlockMatrix polar(layout, depth, 7, 1);  // the second row from the north pole
  EXPECT_TRUE(polar.at(0, -1).exists);
  EXPECT_FALSE(polar.at(0, -2).exists);
  const std::vector<RingoBlockUpdate> north = polar.recentre(7, 0);
  EXPECT_FALSE(polar.at(0, -1).exists);
  int removed = 0;
  for (const RingoBlockUpdate& u : north) removed += u.source == RingoBlockSource::Removed;
  EXPECT_EQ(removed, 11);  // the row that went beyond the pole
}

}  // namespace
}  // namespace tellus
