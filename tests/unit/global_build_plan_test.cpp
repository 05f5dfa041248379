// How the sharded global build splits and lays out its quadtree (global_build_plan.hpp): the
// post-order that makes a store's bytes independent of ranks and threads, the split depth, and
// the deal of subtrees to ranks.
#include <algorithm>
#include <map>
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

TEST(GlobalBuildPlan, SplitDepthSharesTheWorkEvenly) {
  // The whole globe to depth 3 at 1 a tile (a global source), and a fine source over one corner
  // of the tile (3, 5, 2) down to depth 8 at 100 a tile: 21 of every 22 parts of the work.
  std::vector<TileWork> tiles;
  for (const GeoTileKey& key : fullTree(3)) tiles.push_back({key, 1.0});
  for (int d = 4; d <= 8; ++d) {
    const int side = 1 << (d - 3);
    for (int y = 0; y < side / 2; ++y) {
      for (int x = 0; x < side / 2; ++x) tiles.push_back({{d, 5 * side + x, 2 * side + y}, 100.0});
    }
  }
  const auto largestShare = [&](int depth) {
    std::map<GeoTileKey, double> subtrees;
    for (const TileWork& t : tiles) {
      if (t.key.depth >= depth) subtrees[ancestorAt(t.key, depth)] += t.cost;
    }
    double largest = 0.0, total = 0.0;
    for (const auto& [root, cost] : subtrees) largest = std::max(largest, cost), total += cost;
    return largest / total;
  };
  // Depth 3 has 128 tiles, but one subtree holds nearly all the work: the split goes deeper.
  EXPECT_GT(largestShare(3), 0.9);
  for (const int ranks : {1, 2, 4, 16}) {
    const int depth = chooseSplitDepth(tiles, ranks);
    EXPECT_LE(largestShare(depth), 1.0 / (8.0 * ranks)) << ranks << " ranks";
    EXPECT_GT(largestShare(depth - 1), 1.0 / (8.0 * ranks)) << "the shallowest such depth";
  }
  // A single tile: nothing to split.
  EXPECT_EQ(chooseSplitDepth({{{0, 0, 0}, 5.0}}, 4), 0);
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
