#pragma once
// 2D gradient (Perlin-style) noise with analytic derivatives, seeded, deterministic on every
// platform (integer hashing, no tables shared between seeds). Cost: O(1) per sample.
#include <cstdint>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

namespace tellus {

class GradientNoise {
 public:
  explicit GradientNoise(std::uint64_t seed) : seed_(seed) {}

  // Returns (value, d/dx, d/dy) at p. The value lies roughly in [-0.7, 0.7]; it is 0 at integer
  // lattice points.
  glm::dvec3 sample(glm::dvec2 p) const;
  // 3D gradient noise at p (no derivatives): roughly [-1, 1], 0 at integer lattice points
  // (carving caves in material stacks).
  double sample3(glm::dvec3 p) const;

 private:
  glm::dvec2 gradient(std::int64_t ix, std::int64_t iy) const;
  std::uint64_t seed_;
};

}  // namespace tellus
