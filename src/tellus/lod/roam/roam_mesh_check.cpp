#include "tellus/lod/roam/roam_mesh_check.hpp"

#include <cstdint>
#include <unordered_map>

namespace tellus::roam {
namespace {

std::uint64_t pointKey(glm::ivec2 p) {
  return (std::uint64_t(std::uint32_t(p.x)) << 32) | std::uint32_t(p.y);
}

struct EdgeKeyHash {
  std::size_t operator()(const std::pair<std::uint64_t, std::uint64_t>& e) const noexcept {
    return std::hash<std::uint64_t>{}(e.first * 0x9E3779B97F4A7C15ull ^ e.second);
  }
};

}  // namespace

Status checkConforming(const std::vector<BintreeTriangle>& leaves, const BintreeDomain& domain) {
  const int side = domain.blockCells();
  const std::int64_t width = std::int64_t(domain.blocksX) * side;
  const std::int64_t height = std::int64_t(domain.blocksY) * side;
  std::int64_t twiceArea = 0;
  std::unordered_map<std::pair<std::uint64_t, std::uint64_t>, int, EdgeKeyHash> edges;
  for (const BintreeTriangle& t : leaves) {
    const glm::ivec2 e1 = t.left - t.apex, e2 = t.right - t.apex;
    const std::int64_t cross = std::int64_t(e1.x) * e2.y - std::int64_t(e1.y) * e2.x;
    if (cross <= 0) {
      return makeError("leaf ({},{}) ({},{}) ({},{}) is not counter-clockwise", t.apex.x, t.apex.y,
                       t.left.x, t.left.y, t.right.x, t.right.y);
    }
    twiceArea += cross;
    const glm::ivec2 corners[3] = {t.apex, t.left, t.right};
    for (int k = 0; k < 3; ++k) {
      std::uint64_t a = pointKey(corners[k]), b = pointKey(corners[(k + 1) % 3]);
      if (a > b) std::swap(a, b);
      ++edges[{a, b}];
    }
  }
  if (twiceArea != 2 * width * height) {
    return makeError("the leaves cover {} cells, the domain has {}", double(twiceArea) / 2.0,
                     width * height);
  }
  for (const auto& [edge, count] : edges) {
    const glm::ivec2 a(int(edge.first >> 32), int(edge.first & 0xffffffffu));
    const glm::ivec2 b(int(edge.second >> 32), int(edge.second & 0xffffffffu));
    const bool outline = (a.x == b.x && (a.x == 0 || a.x == width)) ||
                         (a.y == b.y && (a.y == 0 || a.y == height));
    if (count != (outline ? 1 : 2)) {
      return makeError("edge ({},{})-({},{}) is shared by {} leaves (a crack or an overlap)", a.x,
                       a.y, b.x, b.y, count);
    }
  }
  return {};
}

}  // namespace tellus::roam
