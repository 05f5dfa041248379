// The octree renderer's mesh cache bookkeeping (lod/stacks/node_mesh_cache.hpp): first-fit
// ranges that merge when freed, least-recently-used eviction that spares the meshes of the
// frame being drawn.
#include <gtest/gtest.h>

#include "tellus/lod/stacks/node_mesh_cache.hpp"

namespace tellus {
namespace {

TEST(RangeAllocator, FirstFitAndMergesFreedNeighbours) {
  RangeAllocator pool(100);
  EXPECT_EQ(pool.allocate(30), 0u);
  EXPECT_EQ(pool.allocate(30), 30u);
  EXPECT_EQ(pool.allocate(30), 60u);
  EXPECT_FALSE(pool.allocate(30));
  EXPECT_EQ(pool.used(), 90u);
  pool.release(0, 30);
  pool.release(60, 30);
  EXPECT_EQ(pool.largestFree(), 40u);  // 60..100
  EXPECT_FALSE(pool.allocate(50));
  pool.release(30, 30);  // merges with both sides: one range of 100
  EXPECT_EQ(pool.largestFree(), 100u);
  EXPECT_EQ(pool.used(), 0u);
  EXPECT_EQ(pool.allocate(100), 0u);
  EXPECT_FALSE(pool.allocate(0));
}

TEST(NodeMeshCache, EvictsLeastRecentlyUsedButNotThisFramesMeshes) {
  NodeMeshCache cache(100, 600);
  ASSERT_TRUE(cache.insert({1, 0}, 40, 240, 1));
  ASSERT_TRUE(cache.insert({2, 0}, 40, 240, 2));
  EXPECT_TRUE(cache.use({1, 0}, 3));  // 1 is now the most recently used
  // 3 needs room: 2 (used in frame 2) goes, not 1.
  ASSERT_TRUE(cache.insert({3, 0}, 40, 240, 3));
  EXPECT_TRUE(cache.contains({1, 0}));
  EXPECT_FALSE(cache.contains({2, 0}));
  EXPECT_EQ(cache.evictions(), 1u);
  // In frame 3 both meshes are in use: a fourth cannot be placed.
  EXPECT_FALSE(cache.insert({4, 0}, 40, 240, 3));
  EXPECT_TRUE(cache.contains({1, 0}));
  EXPECT_TRUE(cache.contains({3, 0}));
  // Another stitch mask of a node is another mesh; empty meshes take no room.
  EXPECT_TRUE(cache.insert({1, 5}, 0, 0, 3));
  EXPECT_TRUE(cache.contains({1, 5}));
  // Next frame the old ones may go.
  const std::optional<CachedNodeMesh> placed = cache.insert({4, 0}, 60, 300, 4);
  ASSERT_TRUE(placed);
  EXPECT_EQ(cache.vertexPool().used(), 60u + (cache.contains({1, 0}) ? 40u : 0u) +
                                           (cache.contains({3, 0}) ? 40u : 0u));
  EXPECT_FALSE(cache.insert({5, 0}, 101, 6, 5));  // larger than the pool
}

}  // namespace
}  // namespace tellus
