// How the sharded global build splits and lays out its quadtree (global_build_plan.hpp): the
// post-order that makes a store's bytes independent of ranks and threads, the split depth, and
// the deal of subtrees to ranks.
#include <algorithm>
#include <set>

#include <gtest/gtest.h>

#include "tellus/tiles/global_build_plan.hpp"

namespace tellus {
namespace {

// Every tile of depths 0..deepest.
std::vector<GeoTileKey> fullTree(int deepest) {
  std::vector<GeoTileKey> keys;
  for (int d = 0; d <= deepest; ++d) {
    for (int y = 0; y < GlobalTiling::tilesY(d); ++y) {
      for (int x = 0; x < GlobalTiling::tilesX(d); ++x) keys.push_back({d, x, y});
    }
  }
  return keys;
}

// The post-order by its definition: walk the tree recursively, children NW, NE, SW, SE.
void walk(GeoTileKey key, int deepest, std::vector<GeoTileKey>& out) {
  if (key.depth < deepest) {
    for (const GeoTileKey& child : GlobalTiling::children(key)) walk(child, deepest, out);
  }
  out.push_back(key);
}

TEST(GlobalBuildPlan, PostOrderIsTheRecursiveWalk) {
  std::vector<GeoTileKey> expected;
  walk({0, 0, 0}, 3, expected);
  walk({0, 1, 0}, 3, expected);
  std::vector<GeoTileKey> sorted = fullTree(3);
  std::sort(sorted.begin(), sorted.end(), postOrderLess);
  EXPECT_EQ(sorted, expected);
}

TEST(GlobalBuildPlan, EverySubtreeIsOneRunInPostOrder) {
  std::vector<GeoTileKey> sorted = fullTree(4);
  std::sort(sorted.begin(), sorted.end(), postOrderLess);
  for (int split = 0; split <= 4; ++split) {
    // The tiles under each root of depth `split` are contiguous and end with the root.
    std::set<GeoTileKey> finished;
    GeoTileKey current{-1, 0, 0};
    for (const GeoTileKey& key : sorted) {
      if (key.depth < split) continue;
      const GeoTileKey root = ancestorAt(key, split);
      if (root != current) {
        EXPECT_FALSE(finished.count(root)) << "subtree split in two at depth " << split;
        if (current.depth >= 0) finished.insert(current);
        current = root;
      }
      if (key.depth == split) {
        EXPECT_EQ(key, root);
      }
    }
  }
}

TEST(GlobalBuildPlan, AncestorAt) {
  EXPECT_EQ(ancestorAt({3, 13, 6}, 3), (GeoTileKey{3, 13, 6}));
  EXPECT_EQ(ancestorAt({3, 13, 6}, 1), (GeoTileKey{1, 3, 1}));
  EXPECT_EQ(ancestorAt({3, 13, 6}, 0), (GeoTileKey{0, 1, 0}));
}

TEST(GlobalBuildPlan, SplitDepthHasEnoughSubtreesForTheRanks) {
  const std::vector<std::size_t> perDepth{2, 8, 32, 128, 300, 900, 2000};
  EXPECT_EQ(chooseSplitDepth(perDepth, 1), 3);  // at least 64
  EXPECT_EQ(chooseSplitDepth(perDepth, 8), 3);
  EXPECT_EQ(chooseSplitDepth(perDepth, 16), 3);  // at least 128
  EXPECT_EQ(chooseSplitDepth(perDepth, 17), 4);  // at least 136
  EXPECT_EQ(chooseSplitDepth(perDepth, 64), 5);
  EXPECT_EQ(chooseSplitDepth(perDepth, 512), 6) << "at most 1024 wanted";
  EXPECT_EQ(chooseSplitDepth({2, 8, 32, 128, 300}, 1000), 4) << "no depth has enough: the deepest";
  EXPECT_EQ(chooseSplitDepth({2}, 4), 0);
}

TEST(GlobalBuildPlan, DealsContiguousRunsOfEqualWork) {
  // One heavy subtree among light ones.
  std::vector<double> costs(40, 1.0);
  costs[10] = 40.0;
  const std::vector<int> owner = dealContiguous(costs, 4);
  EXPECT_TRUE(std::is_sorted(owner.begin(), owner.end()));
  std::vector<double> work(4, 0.0);
  for (std::size_t i = 0; i < costs.size(); ++i) work[std::size_t(owner[i])] += costs[i];
  EXPECT_EQ(owner.front(), 0);
  EXPECT_EQ(owner.back(), 3);
  for (double w : work) EXPECT_LE(w, 40.0 + 10.0);  // no share beyond the heavy one plus a quarter
  // Fewer subtrees than ranks: some ranks get none, nothing is lost.
  EXPECT_EQ(dealContiguous({5.0, 5.0}, 7).size(), 2u);
  EXPECT_EQ(dealContiguous({}, 3).size(), 0u);
}

}  // namespace
}  // namespace tellus
