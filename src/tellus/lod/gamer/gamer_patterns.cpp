#include "tellus/lod/gamer/gamer_patterns.hpp"

#include <algorithm>
#include <array>
#include <cmath>

#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>

namespace tellus::gamer {
namespace {

using Lattice = glm::ivec2;  // (a, b); c = N - a - b

// Appends triangle (p, q, r) counter-clockwise in the lattice.
void addTriangle(std::vector<std::uint16_t>& out, const std::vector<std::uint16_t>& indexOf, int n,
                 Lattice p, Lattice q, Lattice r) {
  const long long area = static_cast<long long>(q.x - p.x) * (r.y - p.y) - static_cast<long long>(q.y - p.y) * (r.x - p.x);
  if (area == 0) return;  // cannot happen for the constructions below; never emit a degenerate
  if (area < 0) std::swap(q, r);
  for (const Lattice& v : {p, q, r}) out.push_back(indexOf[std::size_t(v.x) * std::size_t(n + 1) + std::size_t(v.y)]);
}

// Uniform subdivision of the triangle (origin, origin + (k*step, 0), origin + (0, k*step)).
void addUniform(std::vector<std::uint16_t>& out, const std::vector<std::uint16_t>& indexOf, int n,
                Lattice origin, int k, int step) {
  for (int i = 0; i < k; ++i) {
    for (int j = 0; i + j < k; ++j) {
      const Lattice p = origin + Lattice(i, j) * step;
      addTriangle(out, indexOf, n, p, p + Lattice(step, 0), p + Lattice(0, step));
      if (i + j < k - 1) {
        addTriangle(out, indexOf, n, p + Lattice(step, 0), p + Lattice(step, step), p + Lattice(0, step));
      }
    }
  }
}

// The points from `from` to `to` in `segments` equal steps.
std::vector<Lattice> polyline(Lattice from, Lattice to, int segments) {
  std::vector<Lattice> points;
  for (int t = 0; t <= segments; ++t) points.push_back(from + (to - from) * t / segments);
  return points;
}

// Triangulates the band between polylines `outer` and `inner` running the same way: each step
// advances along the one whose next point comes first (by the fraction of its length).
void zip(std::vector<std::uint16_t>& out, const std::vector<std::uint16_t>& indexOf, int n,
         const std::vector<Lattice>& outer, const std::vector<Lattice>& inner) {
  const int no = int(outer.size()) - 1, ni = int(inner.size()) - 1;
  int i = 0, j = 0;
  while (i < no || j < ni) {
    // Compare (i + 1) / no with (j + 1) / ni without division.
    const bool advanceOuter = j == ni || (i < no && static_cast<long long>(i + 1) * ni <= static_cast<long long>(j + 1) * no);
    if (advanceOuter) {
      addTriangle(out, indexOf, n, outer[std::size_t(i)], outer[std::size_t(i) + 1], inner[std::size_t(j)]);
      ++i;
    } else {
      addTriangle(out, indexOf, n, outer[std::size_t(i)], inner[std::size_t(j) + 1], inner[std::size_t(j)]);
      ++j;
    }
  }
}

using Triangles = std::vector<std::array<Lattice, 3>>;

bool onEdge(int edge, Lattice v, int n) {
  return edge == 0 ? v.x + v.y == n : edge == 1 ? v.x == 0 : v.y == 0;
}

// The seed's simple construction: the uniform subdivision to the smallest depth m, then every
// triangle with a side on an edge of larger depth fanned from its opposite corner into its share
// of that edge's 2^d segments.
Triangles fanPattern(int n, const std::array<int, 3>& depth) {
  const int m = std::min({depth[0], depth[1], depth[2]});
  const int k = 1 << m, step = n >> m;
  Triangles triangles;
  for (int i = 0; i < k; ++i) {
    for (int j = 0; i + j < k; ++j) {
      const Lattice p = Lattice(i, j) * step;
      triangles.push_back({p, p + Lattice(step, 0), p + Lattice(0, step)});
      if (i + j < k - 1) triangles.push_back({p + Lattice(step, 0), p + Lattice(step, step), p + Lattice(0, step)});
    }
  }
  for (int e = 0; e < 3; ++e) {
    const int parts = 1 << (depth[std::size_t(e)] - m);
    if (parts == 1) continue;
    Triangles next;
    for (const auto& t : triangles) {
      int side = -1;
      for (int s = 0; s < 3; ++s) {
        if (onEdge(e, t[std::size_t(s)], n) && onEdge(e, t[std::size_t((s + 1) % 3)], n)) side = s;
      }
      if (side < 0) {
        next.push_back(t);
        continue;
      }
      const Lattice p = t[std::size_t(side)], q = t[std::size_t((side + 1) % 3)], r = t[std::size_t((side + 2) % 3)];
      for (int s = 0; s < parts; ++s) next.push_back({p + (q - p) * s / parts, p + (q - p) * (s + 1) / parts, r});
    }
    triangles.swap(next);
  }
  return triangles;
}

// Smallest angle, degrees, of a triangle placed on the right isosceles coarse triangle (corner 1
// the right angle, as the renderer lays out both halves of a cell).
double smallestAngleDeg(const std::array<Lattice, 3>& t, int n) {
  std::array<glm::dvec2, 3> p;
  for (std::size_t k = 0; k < 3; ++k) {
    const double a = double(t[k].x) / n, b = double(t[k].y) / n, c = 1.0 - a - b;
    p[k] = a * glm::dvec2(0, 0) + b * glm::dvec2(1, 0) + c * glm::dvec2(1, 1);
  }
  double smallest = 180.0;
  for (std::size_t k = 0; k < 3; ++k) {
    const glm::dvec2 u = glm::normalize(p[(k + 1) % 3] - p[k]), v = glm::normalize(p[(k + 2) % 3] - p[k]);
    smallest = std::min(smallest, glm::degrees(std::acos(std::clamp(glm::dot(u, v), -1.0, 1.0))));
  }
  return smallest;
}

// Quality of a candidate: its smallest angle, then (ties) fewer triangles under 30 degrees.
std::pair<double, double> quality(const std::vector<std::uint16_t>& indices, const std::vector<glm::u16vec2>& vertices, int n) {
  double smallest = 180.0;
  std::size_t oblique = 0;
  for (std::size_t i = 0; i + 2 < indices.size(); i += 3) {
    std::array<Lattice, 3> t;
    for (std::size_t k = 0; k < 3; ++k) t[k] = Lattice(vertices[indices[i + k]]);
    const double angle = smallestAngleDeg(t, n);
    smallest = std::min(smallest, angle);
    oblique += angle < 30.0 ? 1 : 0;
  }
  return {smallest, -double(oblique) / double(std::max<std::size_t>(1, indices.size() / 3))};
}

// An inner triangle inset by 2^-max(m, 2) of the edge, subdivided uniformly, and each edge's
// 2^d points zipped to the inner side facing it.
void zipRing(std::vector<std::uint16_t>& out, const std::vector<std::uint16_t>& indexOf, int n,
             const std::array<Lattice, 3>& corner, const std::array<int, 3>& depth, int m) {
  const int inner = std::max(m, 2);
  const int u = n >> inner;
  const int sides = (1 << inner) - 3;  // inner triangle's segments a side (>= 1)
  const std::array<Lattice, 3> innerCorner{Lattice(n - 2 * u, u), Lattice(u, n - 2 * u), Lattice(u, u)};
  addUniform(out, indexOf, n, innerCorner[2], sides, u);
  for (std::size_t e = 0; e < 3; ++e) {
    const std::size_t next = (e + 1) % 3;
    zip(out, indexOf, n, polyline(corner[e], corner[next], 1 << depth[e]), polyline(innerCorner[e], innerCorner[next], sides));
  }
}

}  // namespace

Result<PatternPool> PatternPool::build(int maxDepth) {
  if (maxDepth < 2 || maxDepth > kMaxPatternDepth) {
    return makeError("GAMeR pattern depth {} is outside [2, {}]", maxDepth, kMaxPatternDepth);
  }
  PatternPool pool;
  pool.maxDepth = maxDepth;
  const int n = 1 << maxDepth;
  pool.latticeSteps = n;
  std::vector<std::uint16_t> indexOf(std::size_t(n + 1) * std::size_t(n + 1), 0);
  for (int a = 0; a <= n; ++a) {
    for (int b = 0; a + b <= n; ++b) {
      indexOf[std::size_t(a) * std::size_t(n + 1) + std::size_t(b)] = std::uint16_t(pool.vertices.size());
      pool.vertices.emplace_back(a, b);
    }
  }
  const std::array<Lattice, 3> corner{Lattice(n, 0), Lattice(0, n), Lattice(0, 0)};
  for (int d0 = 0; d0 <= maxDepth; ++d0) {
    for (int d1 = 0; d1 <= maxDepth; ++d1) {
      for (int d2 = 0; d2 <= maxDepth; ++d2) {
        PatternRange range;
        range.firstIndex = std::uint32_t(pool.indices.size());
        const std::array<int, 3> depth{d0, d1, d2};
        const int m = std::min({d0, d1, d2});
        if (d0 == d1 && d1 == d2) {
          addUniform(pool.indices, indexOf, n, corner[2], 1 << m, n >> m);
        } else {
          // Two candidates with the same border, the better-shaped one kept: the seed's fans, and
          // the zipped ring below (better where the depths are close, fans where one is much finer).
          std::vector<std::uint16_t> fans;
          for (const auto& t : fanPattern(n, depth)) addTriangle(fans, indexOf, n, t[0], t[1], t[2]);
          std::vector<std::uint16_t> zipped;
          zipRing(zipped, indexOf, n, corner, depth, m);
          const auto& best = quality(zipped, pool.vertices, n) >= quality(fans, pool.vertices, n) ? zipped : fans;
          pool.indices.insert(pool.indices.end(), best.begin(), best.end());
        }
        range.indexCount = std::uint32_t(pool.indices.size()) - range.firstIndex;
        pool.patterns.push_back(range);
      }
    }
  }
  return pool;
}

PatternShape patternShape(const PatternPool& pool, const PatternRange& range) {
  PatternShape shape;
  shape.minAngleDeg = 180.0;
  std::size_t oblique = 0;
  const std::size_t triangles = range.indexCount / 3;
  for (std::size_t t = 0; t < triangles; ++t) {
    std::array<Lattice, 3> lattice;
    for (std::size_t k = 0; k < 3; ++k) lattice[k] = Lattice(pool.vertices[pool.indices[range.firstIndex + 3 * t + k]]);
    const double smallest = smallestAngleDeg(lattice, pool.latticeSteps);
    shape.minAngleDeg = std::min(shape.minAngleDeg, smallest);
    if (smallest < 30.0) ++oblique;
  }
  shape.obliqueShare = triangles ? double(oblique) / double(triangles) : 0.0;
  return shape;
}

}  // namespace tellus::gamer
