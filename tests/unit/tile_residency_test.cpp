// The GPU tile cache's policy (GL-free): LRU by last-use frame, nothing used in the current frame
// or pinned is evicted, the page table follows every move, and a patch may only draw from a
// level whose tiles are resident on it and every coarser level.
#include <gtest/gtest.h>

#include "tellus/lod/rings/tile_residency.hpp"

namespace tellus {
namespace {

PyramidLayout layout() {
  // 1025 x 1025 samples in 64-cell tiles: 16x16, 8x8, 4x4, 2x2, 1x1 tiles.
  Result<PyramidLayout> l = PyramidLayout::create(1025, 1025, 64);
  EXPECT_TRUE(l);
  return l.value();
}

TEST(TileResidency, PageTableCoversThePyramid) {
  Result<TileResidency> r = TileResidency::create(layout(), 4);
  ASSERT_TRUE(r);
  EXPECT_EQ(r->levelCount(), 5);
  EXPECT_EQ(r->pageTable().size(), std::size_t(256 + 64 + 16 + 4 + 1));
  EXPECT_EQ(r->levelOffset(1), 256);
  EXPECT_EQ(r->tilesX(2), 4);
  EXPECT_EQ(r->slotOf({2, 3, 3}), -1);
  EXPECT_FALSE(TileResidency::create(layout(), 0));
}

TEST(TileResidency, EvictsTheLeastRecentlyUsedButNeverThisFramesOrPinnedTiles) {
  Result<TileResidency> r = TileResidency::create(layout(), 3);
  ASSERT_TRUE(r);
  r->assign(r->acquireSlot(), {4, 0, 0}, true);  // pinned
  r->beginFrame();
  r->assign(r->acquireSlot(), {3, 0, 0});
  r->beginFrame();
  r->assign(r->acquireSlot(), {3, 1, 0});
  EXPECT_EQ(r->residentCount(), 3);
  // Full: the oldest unpinned tile goes.
  r->beginFrame();
  r->touch({3, 1, 0});
  const int slot = r->acquireSlot();
  ASSERT_GE(slot, 0);
  EXPECT_EQ(r->slotOf({3, 0, 0}), -1);
  EXPECT_EQ(r->evictions(), 1u);
  r->assign(slot, {2, 0, 0});
  EXPECT_EQ(r->slotOf({2, 0, 0}), slot);
  EXPECT_EQ(r->tileIn(slot), (TileKey{2, 0, 0}));
  // Everything else is pinned or used by this frame: no slot.
  EXPECT_EQ(r->acquireSlot(), -1);
  EXPECT_EQ(r->slotOf({3, 1, 0}), 2);
  // Next frame the least recently used of the two is taken.
  r->beginFrame();
  r->touch({2, 0, 0});
  EXPECT_EQ(r->acquireSlot(), 2);
  EXPECT_EQ(r->slotOf({3, 1, 0}), -1);
  EXPECT_EQ(r->slotOf({4, 0, 0}), 0);
}

TEST(TileResidency, RequestsAreCountedOncePerFrame) {
  Result<TileResidency> r = TileResidency::create(layout(), 2);
  ASSERT_TRUE(r);
  EXPECT_TRUE(r->firstRequestThisFrame({1, 2, 3}));
  EXPECT_FALSE(r->firstRequestThisFrame({1, 2, 3}));
  EXPECT_TRUE(r->firstRequestThisFrame({1, 3, 3}));
  r->beginFrame();
  EXPECT_TRUE(r->firstRequestThisFrame({1, 2, 3}));
}

TEST(TileResidency, ClosedLevelNeedsEveryCoarserTile) {
  Result<TileResidency> r = TileResidency::create(layout(), 8);
  ASSERT_TRUE(r);
  // Nothing resident: not even the coarsest level.
  EXPECT_EQ(r->closedLevel(5, 6, 0), 5);
  r->assign(r->acquireSlot(), {4, 0, 0}, true);
  EXPECT_EQ(r->closedLevel(5, 6, 0), 4);
  // Level-0 tile (5, 6) lies in (2, 3) on level 1, (1, 1) on level 2, (0, 0) on level 3.
  r->assign(r->acquireSlot(), {1, 2, 3});
  EXPECT_EQ(r->closedLevel(5, 6, 0), 4);  // levels 2 and 3 are missing: level 1 is unusable
  r->assign(r->acquireSlot(), {3, 0, 0});
  r->assign(r->acquireSlot(), {2, 1, 1});
  EXPECT_EQ(r->closedLevel(5, 6, 0), 1);
  EXPECT_EQ(r->closedLevel(5, 6, 2), 2);  // never finer than wanted
  EXPECT_EQ(r->closedLevel(4, 6, 0), 1);  // the same level-1 tile
  EXPECT_EQ(r->closedLevel(6, 6, 0), 2);  // level-1 tile (3, 3) is missing
  EXPECT_EQ(r->closedLevel(15, 15, 0), 4);
}

}  // namespace
}  // namespace tellus
