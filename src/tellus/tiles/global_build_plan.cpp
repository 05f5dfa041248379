#include "tellus/tiles/global_build_plan.hpp"

#include <algorithm>
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

int chooseSplitDepth(const std::vector<std::size_t>& tilesPerDepth, int ranks) {
  const std::size_t wanted = std::clamp<std::size_t>(8 * std::size_t(std::max(1, ranks)), 64, 1024);
  for (std::size_t d = 0; d < tilesPerDepth.size(); ++d) {
    if (tilesPerDepth[d] >= wanted) return int(d);
  }
  return std::max(0, int(tilesPerDepth.size()) - 1);
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
