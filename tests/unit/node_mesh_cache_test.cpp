// The octree renderer's mesh cache bookkeeping (lod/stacks/node_mesh_cache.hpp): best-fit
// ranges that merge when freed, least-recently-used eviction that spares the meshes of the
// frame being drawn.
#include <gtest/gtest.h>

#include <cstdio>
#include <map>
#include <random>
#include <vector>

#include "tellus/lod/stacks/node_mesh_cache.hpp"

namespace tellus {
namespace {

TEST(RangeAllocator, AllocatesInOrderAndMergesFreedNeighbours) {
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

TEST(RangeAllocator, TakesTheSmallestRangeThatFits) {
  RangeAllocator pool(100);
  ASSERT_EQ(pool.allocate(50), 0u);
  ASSERT_EQ(pool.allocate(10), 50u);
  ASSERT_EQ(pool.allocate(20), 60u);
  ASSERT_EQ(pool.allocate(20), 80u);
  pool.release(0, 50);   // free: 0..50
  pool.release(60, 20);  // free: 60..80
  EXPECT_EQ(pool.allocate(15), 60u);  // the 20, not the first range
  EXPECT_EQ(pool.allocate(45), 0u);
  EXPECT_EQ(pool.largestFree(), 5u);
}

// Random allocations and releases against a plain model of every element: no two live ranges
// overlap, the counts agree, and an allocation fails only when no free run is long enough.
TEST(RangeAllocator, StaysConsistentUnderFragmentation) {
  constexpr std::uint32_t kCapacity = 5000;
  RangeAllocator pool(kCapacity);
  std::vector<bool> taken(kCapacity, false);
  struct Live {
    std::uint32_t first, count;
  };
  std::vector<Live> live;
  std::mt19937 random(7);
  const auto longestFreeRun = [&] {
    std::uint32_t best = 0, run = 0;
    for (bool t : taken) {
      run = t ? 0 : run + 1;
      best = std::max(best, run);
    }
    return best;
  };
  for (int step = 0; step < 4000; ++step) {
    if (live.empty() || random() % 3 != 0) {
      const auto count = std::uint32_t(1 + random() % 120);
      const std::optional<std::uint32_t> first = pool.allocate(count);
      if (!first) {
        EXPECT_LT(longestFreeRun(), count) << "step " << step;
        continue;
      }
      ASSERT_LE(*first + count, kCapacity);
      for (std::uint32_t e = *first; e < *first + count; ++e) {
        ASSERT_FALSE(taken[e]) << "element " << e << " handed out twice, step " << step;
        taken[e] = true;
      }
      live.push_back({*first, count});
    } else {
      const std::size_t k = random() % live.size();
      pool.release(live[k].first, live[k].count);
      for (std::uint32_t e = live[k].first; e < live[k].first + live[k].count; ++e) taken[e] = false;
      live.erase(live.begin() + std::ptrdiff_t(k));
    }
    std::uint32_t used = 0;
    for (const Live& l : live) used += l.count;
    ASSERT_EQ(pool.used(), used);
    if (step % 50 == 0) {
      EXPECT_EQ(pool.largestFree(), longestFreeRun()) << "step " << step;
    }
  }
  for (const Live& l : live) pool.release(l.first, l.count);
  EXPECT_EQ(pool.largestFree(), kCapacity);  // everything merged back into one range
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

// A slot hint finds the mesh it was made for, marks it used like a keyed look-up, and is never
// taken for another key's mesh once the slot is freed and reused; a stale hint still finds
// the mesh by its key (and is updated).
TEST(NodeMeshCache, SlotHintsFindTheirMeshAndNeverAnotherOne) {
  NodeMeshCache cache(100, 600);
  ASSERT_TRUE(cache.insert({1, 0}, 40, 240, 1));
  ASSERT_TRUE(cache.insert({2, 0}, 40, 240, 1));
  NodeMeshCache::SlotHint hint1, hint2;
  const CachedNodeMesh* one = cache.use({1, 0}, 2, hint1);
  ASSERT_TRUE(one);
  EXPECT_EQ(one->vertexCount, 40u);
  EXPECT_EQ(cache.use({1, 0}, 2, hint1), one);  // through the hint now
  EXPECT_EQ(one->lastUsedFrame, 2u);
  ASSERT_TRUE(cache.use({2, 0}, 2, hint2));
  EXPECT_NE(hint1.slot, hint2.slot);
  // A hint given for another key's slot is not taken for it.
  NodeMeshCache::SlotHint wrong = hint2;
  EXPECT_EQ(cache.use({1, 0}, 3, wrong), one);
  EXPECT_EQ(wrong.slot, hint1.slot);
  // Mesh 1 is evicted (2 is used in frame 4) and its slot reused by mesh 3: the hint finds
  // nothing for key 1, and key 3's mesh only by its own key.
  ASSERT_TRUE(cache.use({2, 0}, 4, hint2));
  ASSERT_TRUE(cache.insert({3, 0}, 30, 240, 4));
  EXPECT_FALSE(cache.contains({1, 0}));
  NodeMeshCache::SlotHint stale = hint1;
  EXPECT_EQ(cache.use({1, 0}, 4, stale), nullptr);
  const CachedNodeMesh* three = cache.use({3, 0}, 4, stale);
  ASSERT_TRUE(three);
  EXPECT_EQ(three->vertexCount, 30u);
  // A hint at a freed slot (mesh 3 erased by eraseIf) finds nothing.
  NodeMeshCache::SlotHint hint3 = stale;
  EXPECT_EQ(cache.eraseIf([](std::uint64_t node) { return node == 3; }), 1u);
  EXPECT_EQ(cache.use({3, 0}, 5, hint3), nullptr);
  // An unset hint is a keyed look-up.
  NodeMeshCache::SlotHint fresh;
  EXPECT_TRUE(cache.use({2, 0}, 5, fresh));
  EXPECT_EQ(fresh.slot, hint2.slot);
}

// Random frames of look-ups and insertions against a plain model of what is cached: the
// cache holds what it says it holds, at the sizes given, its pools count exactly those, and it
// evicts least recently used first (at the granularity of frames), never a mesh of the frame.
TEST(NodeMeshCache, EvictsTheOldestFramesFirstUnderRandomUse) {
  struct Model {
    std::uint32_t vertices = 0, indices = 0;
    std::uint64_t lastUsed = 0;
  };
  NodeMeshCache cache(4000, 24000);
  std::map<std::uint64_t, Model> model;
  std::mt19937 random(7);
  std::size_t evicted = 0, refused = 0;
  for (std::uint64_t frame = 1; frame <= 300; ++frame) {
    for (int op = 0; op < 40; ++op) {
      const std::uint64_t node = random() % 400;
      const NodeMeshKey key{node, 0};
      if (random() % 2 == 0) {
        const CachedNodeMesh* mesh = cache.use(key, frame);
        ASSERT_EQ(mesh != nullptr, model.contains(node)) << "frame " << frame;
        if (mesh) {
          EXPECT_EQ(mesh->vertexCount, model[node].vertices);
          EXPECT_EQ(mesh->indexCount, model[node].indices);
          model[node].lastUsed = frame;
        }
        continue;
      }
      const std::uint32_t vertices = random() % 5 == 0 ? 0u : 1u + std::uint32_t(random() % 120);
      const std::uint32_t indices = vertices == 0 ? 0u : 3u * vertices;
      model.erase(node);  // a node inserted again replaces its mesh
      const bool placed = cache.insert(key, vertices, indices, frame).has_value();
      refused += placed ? 0 : 1;
      // What went: the least recently used, all older than (or as old as) every survivor,
      // none used in this frame.
      std::uint64_t newestGone = 0, oldestKept = ~std::uint64_t(0);
      for (auto it = model.begin(); it != model.end();) {
        if (cache.contains({it->first, 0})) {
          oldestKept = std::min(oldestKept, it->second.lastUsed);
          ++it;
        } else {
          EXPECT_LT(it->second.lastUsed, frame);
          newestGone = std::max(newestGone, it->second.lastUsed);
          ++evicted;
          it = model.erase(it);
        }
      }
      EXPECT_LE(newestGone, oldestKept) << "frame " << frame;
      if (placed) model[node] = {vertices, indices, frame};
      std::uint32_t usedVertices = 0, usedIndices = 0;
      for (const auto& [n, m] : model) {
        usedVertices += m.vertices;
        usedIndices += m.indices;
      }
      ASSERT_EQ(cache.vertexPool().used(), usedVertices);
      ASSERT_EQ(cache.indexPool().used(), usedIndices);
      ASSERT_EQ(cache.size(), model.size());
    }
  }
  EXPECT_GT(evicted, 1000u);  // the pool was under pressure throughout
  std::printf("%zu evicted, %zu refused\n", evicted, refused);
}

}  // namespace
}  // namespace tellus
