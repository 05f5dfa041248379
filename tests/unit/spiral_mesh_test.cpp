// The spiral globe's mesh (seed 001): the radius doubles every spintodouble revolutions, the
// spin step must divide 360, successive revolutions share their vertices, the drawn range with
// its fan is a watertight disc (every inner edge shared by exactly two triangles, no vertex in
// the middle of another triangle's edge), and about as many triangles are drawn at any zoom.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <map>
#include <utility>

#include "tellus/lod/spiral/spiral_mesh.hpp"

namespace tellus {
namespace {

SpiralParams params(double spinStepDeg) {
  return {.spinToDouble = 1.0, .baseRadius = 1e-3, .spinStepDeg = spinStepDeg, .outerRadius = 10.0};
}

TEST(SpiralMesh, TheRadiusDoublesEverySpinToDoubleRevolutions) {
  Result<SpiralMesh> mesh = buildSpiralMesh(params(30.0));
  ASSERT_TRUE(mesh) << mesh.error().message;
  ASSERT_EQ(mesh->perRevolution, 12);
  EXPECT_NEAR(mesh->radiusOf(0), 1e-3, 1e-9);
  EXPECT_NEAR(mesh->radiusOf(12) / mesh->radiusOf(0), 2.0, 1e-6);
  EXPECT_NEAR(mesh->radiusOf(36) / mesh->radiusOf(12), 4.0, 1e-6);
  // Directions repeat exactly every revolution; vertex 3 points east (spin 90).
  EXPECT_EQ(mesh->vertices[5].dirX, mesh->vertices[5 + 12 * 7].dirX);
  EXPECT_EQ(mesh->vertices[5].dirY, mesh->vertices[5 + 12 * 7].dirY);
  EXPECT_NEAR(mesh->vertices[3].dirX, 1.0f, 1e-7f);
  EXPECT_NEAR(mesh->vertices[3].dirY, 0.0f, 1e-7f);
  // Generated out to the outer radius, with a revolution beyond it for the last step's outer
  // vertices.
  EXPECT_GE(mesh->radiusOf(int(mesh->vertices.size()) - 1 - 12), 10.0 * (1 - 1e-6));
  // The strip alternates each inner vertex with the same direction a revolution out.
  for (std::size_t i = 0; i + 1 < mesh->strip.size(); i += 2) {
    EXPECT_EQ(mesh->strip[i + 1], mesh->strip[i] + 12u);
  }
}

TEST(SpiralMesh, ASpinStepThatDoesNotDivide360IsRefused) {
  EXPECT_TRUE(buildSpiralMesh(params(7.5)));   // 48 steps
  EXPECT_TRUE(buildSpiralMesh(params(120.0)));  // 3 steps
  Result<SpiralMesh> seven = buildSpiralMesh(params(7.0));  // 51.43 steps: cracks
  ASSERT_FALSE(seven);
  EXPECT_NE(seven.error().message.find("does not divide 360"), std::string::npos);
  EXPECT_FALSE(buildSpiralMesh(params(180.0)));  // two steps make no revolution
  EXPECT_FALSE(buildSpiralMesh(params(0.0)));
  EXPECT_FALSE(buildSpiralMesh(params(-10.0)));
  SpiralParams bad = params(10.0);
  bad.spinToDouble = 0.0;
  EXPECT_FALSE(buildSpiralMesh(bad));
  bad = params(10.0);
  bad.outerRadius = bad.baseRadius;
  EXPECT_FALSE(buildSpiralMesh(bad));
  bad = params(1e-4);  // billions of vertices
  EXPECT_FALSE(buildSpiralMesh(bad));
}

// The drawn range's triangles, strip then fan (centre: an extra vertex at the origin).
std::vector<std::array<std::uint32_t, 3>> drawnTriangles(const SpiralMesh& mesh,
                                                         const SpiralRange& range,
                                                         std::uint32_t centre) {
  std::vector<std::array<std::uint32_t, 3>> triangles;
  const std::size_t begin = 2 * std::size_t(range.first);
  const std::size_t end = 2 * std::size_t(range.first + range.count) + 2;  // one past the last
  for (std::size_t i = begin; i + 2 < end; ++i) {
    triangles.push_back({mesh.strip[i], mesh.strip[i + 1], mesh.strip[i + 2]});
  }
  const std::vector<std::uint32_t> fan = spiralFan(mesh, range, centre);
  for (std::size_t i = 0; i < fan.size(); i += 3) triangles.push_back({fan[i], fan[i + 1], fan[i + 2]});
  return triangles;
}

TEST(SpiralMesh, TheDrawnRangeAndItsFanAreAWatertightDisc) {
  Result<SpiralMesh> mesh = buildSpiralMesh(params(30.0));
  ASSERT_TRUE(mesh);
  const SpiralRange range = spiralRange(*mesh, 0.01, 0.2);
  ASSERT_GE(range.count, mesh->perRevolution);
  const auto centre = std::uint32_t(mesh->vertices.size());
  const auto triangles = drawnTriangles(*mesh, range, centre);
  const auto position = [&](std::uint32_t v) -> std::pair<double, double> {
    if (v == centre) return {0.0, 0.0};
    const SpiralVertex& s = mesh->vertices[v];
    return {double(s.dirX) * s.radius, double(s.dirY) * s.radius};
  };
  std::map<std::pair<std::uint32_t, std::uint32_t>, int> uses;
  for (const auto& t : triangles) {
    for (int e = 0; e < 3; ++e) {
      const std::uint32_t a = t[std::size_t(e)], b = t[std::size_t((e + 1) % 3)];
      ++uses[{std::min(a, b), std::max(a, b)}];
    }
  }
  // Every edge is shared by two triangles but the outer boundary's; the outer boundary is one
  // closed loop away from the centre (each of its vertices on two boundary edges).
  std::map<std::uint32_t, int> boundaryDegree;
  for (const auto& [edge, count] : uses) {
    ASSERT_LE(count, 2) << edge.first << "-" << edge.second;
    if (count == 1) {
      EXPECT_NE(edge.first, centre);
      EXPECT_NE(edge.second, centre);
      ++boundaryDegree[edge.first];
      ++boundaryDegree[edge.second];
    }
  }
  ASSERT_FALSE(boundaryDegree.empty());
  for (const auto& [vertex, degree] : boundaryDegree) {
    EXPECT_EQ(degree, 2) << "vertex " << vertex;
    EXPECT_GE(position(vertex).first * position(vertex).first +
                  position(vertex).second * position(vertex).second,
              0.2 * 0.2 * 0.25);  // on the outside, not around the hole
  }
  // No T-junction: no drawn vertex lies strictly inside another triangle's edge (a displaced
  // vertex would open a crack there).
  std::vector<std::uint32_t> drawn;
  for (const auto& [edge, count] : uses) {
    drawn.push_back(edge.first);
    drawn.push_back(edge.second);
  }
  for (const auto& [edge, count] : uses) {
    const auto [ax, ay] = position(edge.first);
    const auto [bx, by] = position(edge.second);
    const double length = std::hypot(bx - ax, by - ay);
    for (const std::uint32_t v : drawn) {
      if (v == edge.first || v == edge.second) continue;
      const auto [px, py] = position(v);
      const double cross = (bx - ax) * (py - ay) - (by - ay) * (px - ax);
      const double along = ((px - ax) * (bx - ax) + (py - ay) * (by - ay)) / (length * length);
      const bool onEdge = std::abs(cross) < 1e-9 * length && along > 1e-6 && along < 1 - 1e-6;
      EXPECT_FALSE(onEdge) << "vertex " << v << " inside edge " << edge.first << "-" << edge.second;
    }
  }
}

TEST(SpiralMesh, AboutTheSameTrianglesAtAnyZoom) {
  Result<SpiralMesh> mesh = buildSpiralMesh(
      {.spinToDouble = 0.5, .baseRadius = 1e-6, .spinStepDeg = 5.0, .outerRadius = 4.0});
  ASSERT_TRUE(mesh);
  // The same ratio of radii (a view's minimum to maximum) at zooms 2^10 apart.
  const SpiralRange near = spiralRange(*mesh, 1e-4, 1e-2);
  const SpiralRange far = spiralRange(*mesh, 1e-2, 1.0);
  EXPECT_NEAR(double(near.count) / double(far.count), 1.0, 0.02);
  // 100:1 in radius is 0.5 * log2(100) = 3.3 revolutions of 72 steps, plus the revolution that
  // straddles the minimum radius (its outer edge beyond it, the fan inside).
  EXPECT_NEAR(near.count, (0.5 * std::log2(100.0) + 1.0) * 72.0, 2.0);
}

}  // namespace
}  // namespace tellus
