// GAMeR's GL-free parts (seed 004 section 2.5): the adaptive refinement pattern pool (each
// edge of depth d cut into exactly 2^d segments, the triangle tiled without gap or overlap,
// graded patterns with fewer slivers than fans), and the per-frame depth tags and selection
// (shared edges agree on their depth, the CPU reference meets the error target).
#include <algorithm>
#include <map>

#include <gtest/gtest.h>

#include "tellus/dem/terrain_generator.hpp"
#include "tellus/lod/gamer/gamer_patterns.hpp"
#include "tellus/lod/gamer/gamer_refinement.hpp"

namespace tellus::gamer {
namespace {

TEST(GamerPatterns, EveryPatternCutsEachEdgeIntoTwoToTheDepthSegmentsAndTilesTheTriangle) {
  Result<PatternPool> built = PatternPool::build(5);
  ASSERT_TRUE(built) << built.error().message;
  const PatternPool& pool = built.value();
  const int n = pool.latticeSteps;
  ASSERT_EQ(pool.patterns.size(), 216u);
  for (int d0 = 0; d0 <= 5; ++d0) {
    for (int d1 = 0; d1 <= 5; ++d1) {
      for (int d2 = 0; d2 <= 5; ++d2) {
        const PatternRange& range = pool.pattern(d0, d1, d2);
        ASSERT_EQ(range.indexCount % 3, 0u);
        long long area = 0;
        std::map<std::pair<int, int>, int> edges;  // directed edge -> uses
        for (std::uint32_t i = 0; i < range.indexCount; i += 3) {
          glm::ivec2 v[3];
          for (int k = 0; k < 3; ++k) v[k] = glm::ivec2(pool.vertices[pool.indices[range.firstIndex + i + std::uint32_t(k)]]);
          const long long twice = static_cast<long long>(v[1].x - v[0].x) * (v[2].y - v[0].y) - static_cast<long long>(v[1].y - v[0].y) * (v[2].x - v[0].x);
          ASSERT_GT(twice, 0) << "pattern " << d0 << d1 << d2 << ": a degenerate or clockwise triangle";
          area += twice;
          for (int k = 0; k < 3; ++k) {
            ++edges[{pool.indices[range.firstIndex + i + std::uint32_t(k)], pool.indices[range.firstIndex + i + std::uint32_t((k + 1) % 3)]}];
          }
        }
        EXPECT_EQ(area, static_cast<long long>(n) * n) << "pattern " << d0 << d1 << d2 << " does not tile the triangle";
        // Border: directed edges without their reverse; each on one side, 2^d of them there.
        int border[3] = {0, 0, 0};
        for (const auto& [e, uses] : edges) {
          EXPECT_EQ(uses, 1);
          if (edges.count({e.second, e.first})) continue;
          const glm::ivec2 a(pool.vertices[std::size_t(e.first)]), b(pool.vertices[std::size_t(e.second)]);
          if (a.x + a.y == n && b.x + b.y == n) ++border[0];  // corner 0 (n, 0) to corner 1 (0, n)
          else if (a.x == 0 && b.x == 0) ++border[1];
          else if (a.y == 0 && b.y == 0) ++border[2];
          else ADD_FAILURE() << "pattern " << d0 << d1 << d2 << ": an open edge inside the triangle";
        }
        EXPECT_EQ(border[0], 1 << d0);
        EXPECT_EQ(border[1], 1 << d1);
        EXPECT_EQ(border[2], 1 << d2);
      }
    }
  }
}

TEST(GamerPatterns, EqualDepthsGiveTheUniformSubdivision) {
  Result<PatternPool> pool = PatternPool::build(4);
  ASSERT_TRUE(pool);
  for (int d = 0; d <= 4; ++d) EXPECT_EQ(pool->pattern(d, d, d).indexCount / 3, 1u << (2 * d));
}

TEST(GamerPatterns, MixedPatternsAreNoWorseThanTheSeedsFans) {
  Result<PatternPool> pool = PatternPool::build(5);
  ASSERT_TRUE(pool);
  // The seed's Figure 7 configuration {3, 4, 5}: the simple construction (uniform to depth 3,
  // triangles on the finer edges fanned) has a smallest angle of 8.13 degrees there.
  const PatternShape shape = patternShape(pool.value(), pool->pattern(3, 4, 5));
  EXPECT_GE(shape.minAngleDeg, 8.13 - 1e-6);
  // Neighbouring depths (the common case: tags change by one between coarse vertices): no
  // triangle thinner than 10 degrees.
  for (int d = 1; d <= 5; ++d) {
    EXPECT_GT(patternShape(pool.value(), pool->pattern(d - 1, d, d)).minAngleDeg, 10.0) << d;
    EXPECT_GT(patternShape(pool.value(), pool->pattern(d, d - 1, d)).minAngleDeg, 10.0) << d;
    EXPECT_GT(patternShape(pool.value(), pool->pattern(d, d, d - 1)).minAngleDeg, 10.0) << d;
  }
}

TEST(GamerPatterns, UniformPatternsAreRightAngledAndBadDepthsAreRefused) {
  Result<PatternPool> pool = PatternPool::build(5);
  ASSERT_TRUE(pool);
  for (int d = 0; d <= 5; ++d) {
    const PatternShape shape = patternShape(pool.value(), pool->pattern(d, d, d));
    EXPECT_NEAR(shape.minAngleDeg, 45.0, 1e-6);
    EXPECT_EQ(shape.obliqueShare, 0.0);
  }
  EXPECT_FALSE(PatternPool::build(1));
  EXPECT_FALSE(PatternPool::build(kMaxPatternDepth + 1));
}

}  // namespace
}  // namespace tellus::gamer
