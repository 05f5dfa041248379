#include "tellus/tiles/global_build_plan.hpp"

#include <algorithm>
#include <limits>
#include <map>
#include <numeric>
#include <tuple>

namespace tellus {

GeoTileKey ancestorAt(GeoTileKey key, int depth) {
  const int shift = key.depth - depth;
  return {depth, key.x >> shift, key.y >> shift};
}

bool postOrderLess(GeoTileKey a, GeoTileKey b) {
  if (a == b) return false;
  const int common = std::min(a.depth, b.depth);
  if (ancestorAt(a, common) == ancestorAt(b, common)) return a.depth > b.depth;
  // They part at the shallowest depth where their ancestors differ: those are siblings (or the
  // two roots), ordered NW, NE, SW, SE, i.e. by (y, x).
  for (int d = 0; d <= common; ++d) {
    const GeoTileKey pa = ancestorAt(a, d), pb = ancestorAt(b, d);
    if (pa != pb) return std::tie(pa.y, pa.x) < std::tie(pb.y, pb.x);
  }
  return false;  // not reached
}

int chooseSplitDepth(const std::vector<TileWork>& tiles, int ranks) {
  int deepest = 0;
  for (const TileWork& t : tiles) deepest = std::max(deepest, t.key.depth);
  int best = 0;
  double bestShare = std::numeric_limits<double>::infinity();
  for (int depth = 0; depth <= deepest; ++depth) {
    // The tiles above the split are made from their children's samples, not warped: the ranks'
    // work is the subtrees'.
    std::map<GeoTileKey, double> subtrees;
    double total = 0.0;
    for (const TileWork& t : tiles) {
      if (t.key.depth < depth) continue;
      subtrees[ancestorAt(t.key, depth)] += t.cost;
      total += t.cost;
    }
    if (subtrees.size() > kMaxSubtrees) break;  // deeper depths have more
    double largest = 0.0;
    for (const auto& [root, cost] : subtrees) largest = std::max(largest, cost);
    const double share = total > 0.0 ? largest / total : 1.0;
    if (share <= 1.0 / (8.0 * double(std::max(1, ranks)))) return depth;
    if (share < bestShare) best = depth, bestShare = share;
  }
  return best;
}

std::vector<int> dealContiguous(const std::vector<double>& costs, int ranks) {
  const double total = std::accumulate(costs.begin(), costs.end(), 0.0);
  std::vector<int> owner(costs.size(), 0);
  double before = 0.0;
  for (std::size_t i = 0; i < costs.size(); ++i) {
    const double middle = before + 0.5 * costs[i];
    owner[i] = total > 0.0 ? std::clamp(int(middle / total * ranks), 0, ranks - 1) : 0;
    before += costs[i];
  }
  return owner;
}

}  // namespace tellus
