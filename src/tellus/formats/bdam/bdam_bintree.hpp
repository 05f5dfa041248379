#pragma once
// The triangle bintree BDAM's patches live on (seed 004 section 2.2; Cignoni et al. 2003): a
// square domain of 2^domainLog2 cells a side, split along its south-west / north-east diagonal
// into two root triangles, each triangle split at its hypotenuse's midpoint into two children.
// Coordinates are grid samples: x east of the western column, y north of the southern row; the
// grid occupies [0, width - 1] x [0, height - 1] of the domain.
//
// Nodes are heap numbered: the roots are 2 and 3 (level 0), the children of n are 2n and 2n + 1
// (level + 1). A level-l triangle covers 2^(2 * domainLog2 - l) half-cells; at level
// 2 * domainLog2 it is half a grid cell.
#include <array>
#include <cstdint>

#include <glm/vec2.hpp>

namespace tellus::bdam {

using NodeId = std::uint64_t;

struct Triangle {
  glm::ivec2 apex;   // the right angle
  glm::ivec2 left;   // hypotenuse from left to right
  glm::ivec2 right;

  glm::ivec2 hypotenuseMidpoint() const { return (left + right) / 2; }
  // Children: (midpoint, apex, left) is 2n and (midpoint, right, apex) is 2n + 1.
  Triangle child(int which) const {
    const glm::ivec2 m = hypotenuseMidpoint();
    return which == 0 ? Triangle{m, apex, left} : Triangle{m, right, apex};
  }
  glm::ivec2 boxMin() const;
  glm::ivec2 boxMax() const;
};

inline int nodeLevel(NodeId node) {
  int level = -1;
  while (node > 1) {
    node >>= 1;
    ++level;
  }
  return level;
}

// The triangle of `node` in a domain of 2^domainLog2 cells (domainLog2 <= 16).
Triangle nodeTriangle(NodeId node, int domainLog2);

// False when the triangle's box misses the grid's (a cheap test: a true triangle may still hold
// no half-cell of the grid, and then its patch is empty).
bool touchesGrid(const Triangle& t, int width, int height);

// Twice the signed area of (a, b, c): > 0 when counter-clockwise (x east, y north).
inline long long orient(glm::ivec2 a, glm::ivec2 b, glm::ivec2 c) {
  return static_cast<long long>(b.x - a.x) * (c.y - a.y) - static_cast<long long>(b.y - a.y) * (c.x - a.x);
}

// True when p lies on segment [a, b].
bool onSegment(glm::ivec2 p, glm::ivec2 a, glm::ivec2 b);

}  // namespace tellus::bdam
