#pragma once
// GAMeR's adaptive refinement patterns (seed 004 section 2.5; Boubekeur & Schlick 2005): for
// every triple of edge depth tags (d0, d1, d2), 0 <= d <= maxDepth, a triangulation of the unit
// triangle whose edge e is cut into exactly 2^de segments. All patterns index one vertex buffer:
// the barycentric lattice of step 2^-maxDepth.
//
// Corners and edges: corner 0, 1, 2 in counter-clockwise order; edge 0 runs from corner 0 to
// corner 1, edge 1 from 1 to 2, edge 2 from 2 to 0. A lattice vertex (a, b) stands for the
// barycentric weights (a, b, N - a - b) / N on corners (0, 1, 2), N = 2^maxDepth; a pattern
// vertex on an edge therefore lies at a dyadic fraction of it, so two coarse triangles that give
// a shared edge the same depth place the same points on it (no crack, whatever their interiors).
//
// Construction, with m = min(d0, d1, d2): an equal triple is the uniform subdivision (4^m
// right-angled triangles). Otherwise two candidates with the same border are built and the
// better-shaped one kept (the larger smallest angle on the right isosceles coarse triangle, then
// fewer triangles under 30 degrees): the seed's simple construction (uniform to depth m, each
// triangle on a finer edge fanned from its opposite corner), and a zipped ring (an inner
// triangle inset by 2^-max(m, 2) of the edge, subdivided uniformly, each edge's 2^d points
// zipped to the inner side facing it), which grades better where the depths are close.
#include <cstddef>
#include <cstdint>
#include <vector>

#include <glm/vec2.hpp>

#include "tellus/core/result.hpp"

namespace tellus::gamer {

inline constexpr int kMaxPatternDepth = 7;  // lattice of 2^7 steps: 8385 vertices, uint16 indices

struct PatternRange {
  std::uint32_t firstIndex = 0;  // into PatternPool::indices
  std::uint32_t indexCount = 0;  // three per triangle
};

struct PatternPool {
  int maxDepth = 0;
  int latticeSteps = 1;                      // N = 2^maxDepth
  std::vector<glm::u16vec2> vertices;        // lattice (a, b), a + b <= N
  std::vector<std::uint16_t> indices;        // every pattern's triangles, counter-clockwise
  std::vector<PatternRange> patterns;        // (maxDepth + 1)^3, by patternIndex()

  // Errors: maxDepth outside [2, kMaxPatternDepth].
  static Result<PatternPool> build(int maxDepth);

  std::size_t patternIndex(int d0, int d1, int d2) const {
    const std::size_t n = std::size_t(maxDepth) + 1;
    return (std::size_t(d0) * n + std::size_t(d1)) * n + std::size_t(d2);
  }
  const PatternRange& pattern(int d0, int d1, int d2) const { return patterns[patternIndex(d0, d1, d2)]; }
  // GPU memory of the pool: the lattice (2 x uint16 a vertex) and every pattern's indices.
  std::size_t bytes() const {
    return vertices.size() * sizeof(glm::u16vec2) + indices.size() * sizeof(std::uint16_t);
  }
};

// Shape statistics of a pattern drawn on the right isosceles coarse triangle (corner 1 the right
// angle, as the renderer lays out both halves of a grid cell): its smallest angle and the share
// of triangles with an angle under 30 degrees.
struct PatternShape {
  double minAngleDeg = 0.0;
  double obliqueShare = 0.0;  // triangles with an angle < 30 degrees / all
};
PatternShape patternShape(const PatternPool& pool, const PatternRange& range);

}  // namespace tellus::gamer
