#pragma once
// Axis-aligned box in world metres (double precision; see world_frame.hpp for the axes).
#include <algorithm>
#include <array>
#include <cmath>

#include <glm/common.hpp>
#include <glm/vec3.hpp>

namespace tellus {

struct Aabb {
  glm::dvec3 min{0.0};
  glm::dvec3 max{0.0};

  glm::dvec3 centre() const { return (min + max) * 0.5; }
  glm::dvec3 size() const { return max - min; }

  // The 8 corners; bit 0 selects x, bit 1 y, bit 2 z (0 = min, 1 = max).
  std::array<glm::dvec3, 8> corners() const {
    std::array<glm::dvec3, 8> out{};
    for (int i = 0; i < 8; ++i) {
      out[static_cast<size_t>(i)] = {(i & 1) ? max.x : min.x, (i & 2) ? max.y : min.y,
                                     (i & 4) ? max.z : min.z};
    }
    return out;
  }

  // Euclidean distance from p to the box (0 when p is inside). Metres.
  double distanceTo(const glm::dvec3& p) const {
    const glm::dvec3 d = glm::max(glm::max(min - p, p - max), glm::dvec3(0.0));
    return std::sqrt(d.x * d.x + d.y * d.y + d.z * d.z);
  }
};

}  // namespace tellus
