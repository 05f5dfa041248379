#include "tellus/dem/gradient_noise.hpp"

#include <array>
#include <cmath>

#include <glm/glm.hpp>

namespace tellus {
namespace {

std::uint64_t mix64(std::uint64_t x) {  // splitmix64 finaliser
  x ^= x >> 30;
  x *= 0xbf58476d1ce4e5b9ULL;
  x ^= x >> 27;
  x *= 0x94d049bb133111ebULL;
  x ^= x >> 31;
  return x;
}

// 256 unit gradients evenly spread around the circle, picked by the lattice point's hash.
const std::array<glm::dvec2, 256>& gradientTable() {
  static const std::array<glm::dvec2, 256> table = [] {
    std::array<glm::dvec2, 256> t{};
    for (size_t i = 0; i < t.size(); ++i) {
      const double angle = (double(i) + 0.5) * (6.283185307179586 / 256.0);
      t[i] = {std::cos(angle), std::sin(angle)};
    }
    return t;
  }();
  return table;
}

}  // namespace

glm::dvec2 GradientNoise::gradient(std::int64_t ix, std::int64_t iy) const {
  const std::uint64_t h =
      mix64(seed_ ^ mix64(std::uint64_t(ix) * 0x9E3779B97F4A7C15ULL + std::uint64_t(iy)));
  return gradientTable()[h >> 56];
}

glm::dvec3 GradientNoise::sample(glm::dvec2 p) const {
  const double fx = std::floor(p.x), fy = std::floor(p.y);
  const auto ix = std::int64_t(fx), iy = std::int64_t(fy);
  const glm::dvec2 f = p - glm::dvec2(fx, fy);
  // Quintic fade and its derivative.
  const glm::dvec2 u = f * f * f * (f * (f * 6.0 - 15.0) + 10.0);
  const glm::dvec2 du = 30.0 * f * f * (f * (f - 2.0) + 1.0);

  const glm::dvec2 ga = gradient(ix, iy), gb = gradient(ix + 1, iy);
  const glm::dvec2 gc = gradient(ix, iy + 1), gd = gradient(ix + 1, iy + 1);
  const double va = glm::dot(ga, f), vb = glm::dot(gb, f - glm::dvec2(1, 0));
  const double vc = glm::dot(gc, f - glm::dvec2(0, 1)), vd = glm::dot(gd, f - glm::dvec2(1, 1));

  const double k = va - vb - vc + vd;
  const double value = va + u.x * (vb - va) + u.y * (vc - va) + u.x * u.y * k;
  const glm::dvec2 derivative = ga + u.x * (gb - ga) + u.y * (gc - ga) +
                                u.x * u.y * (ga - gb - gc + gd) +
                                du * (glm::dvec2(u.y, u.x) * k + glm::dvec2(vb - va, vc - va));
  return {value, derivative.x, derivative.y};
}

double GradientNoise::sample3(glm::dvec3 p) const {
  const glm::dvec3 fl = glm::floor(p);
  const glm::dvec3 f = p - fl;
  const auto ix = std::int64_t(fl.x), iy = std::int64_t(fl.y), iz = std::int64_t(fl.z);
  const glm::dvec3 u = f * f * f * (f * (f * 6.0 - 15.0) + 10.0);
  // The 12 edge directions of a cube (Perlin's improved noise), picked by the corner's hash.
  static const glm::dvec3 kEdges[12] = {{1, 1, 0}, {-1, 1, 0}, {1, -1, 0}, {-1, -1, 0},
                                        {1, 0, 1}, {-1, 0, 1}, {1, 0, -1}, {-1, 0, -1},
                                        {0, 1, 1}, {0, -1, 1}, {0, 1, -1}, {0, -1, -1}};
  const auto corner = [&](int dx, int dy, int dz) {
    const std::uint64_t h = mix64(
        seed_ ^ mix64(std::uint64_t(ix + dx) * 0x9E3779B97F4A7C15ULL ^
                      mix64(std::uint64_t(iy + dy) * 0xC2B2AE3D27D4EB4FULL + std::uint64_t(iz + dz))));
    return glm::dot(kEdges[(h >> 32) % 12], f - glm::dvec3(dx, dy, dz));
  };
  const double x00 = glm::mix(corner(0, 0, 0), corner(1, 0, 0), u.x);
  const double x10 = glm::mix(corner(0, 1, 0), corner(1, 1, 0), u.x);
  const double x01 = glm::mix(corner(0, 0, 1), corner(1, 0, 1), u.x);
  const double x11 = glm::mix(corner(0, 1, 1), corner(1, 1, 1), u.x);
  return glm::mix(glm::mix(x00, x10, u.y), glm::mix(x01, x11, u.y), u.z);
}

}  // namespace tellus
