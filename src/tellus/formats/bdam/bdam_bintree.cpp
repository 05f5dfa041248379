#include "tellus/formats/bdam/bdam_bintree.hpp"

#include <algorithm>

#include <glm/common.hpp>

namespace tellus::bdam {

glm::ivec2 Triangle::boxMin() const { return glm::min(apex, glm::min(left, right)); }
glm::ivec2 Triangle::boxMax() const { return glm::max(apex, glm::max(left, right)); }

Triangle nodeTriangle(NodeId node, int domainLog2) {
  const int side = 1 << domainLog2;
  const int level = nodeLevel(node);
  // Root 2: apex south-east; root 3: apex north-west; both with hypotenuse on the diagonal.
  const NodeId root = node >> level;
  Triangle t = root == 2 ? Triangle{{side, 0}, {0, 0}, {side, side}} : Triangle{{0, side}, {side, side}, {0, 0}};
  for (int bit = level - 1; bit >= 0; --bit) t = t.child(int((node >> bit) & 1u));
  return t;
}

bool touchesGrid(const Triangle& t, int width, int height) {
  const glm::ivec2 lo = t.boxMin(), hi = t.boxMax();
  return lo.x < width - 1 && lo.y < height - 1 && hi.x > 0 && hi.y > 0;
}

bool onSegment(glm::ivec2 p, glm::ivec2 a, glm::ivec2 b) {
  if (orient(a, b, p) != 0) return false;
  return p.x >= std::min(a.x, b.x) && p.x <= std::max(a.x, b.x) && p.y >= std::min(a.y, b.y) &&
         p.y <= std::max(a.y, b.y);
}

}  // namespace tellus::bdam
