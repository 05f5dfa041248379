// GAMeR's GL-free parts (seed 004 section 2.5): the adaptive refinement pattern pool (each
// edge of depth d cut into exactly 2^d segments, the triangle tiled without gap or overlap,
// graded patterns with fewer slivers than fans), and the geomorph of the CPU reference (morph
// depths run continuously from the coarser depth to the tag; a small step of the viewer moves
// the surface little although patterns switch, where without the geomorph whole levels pop; a
// point shared by several triangles gets one height).
#include <algorithm>
#include <cmath>
#include <map>

#include <gtest/gtest.h>

#include "tellus/core/camera.hpp"
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

TEST(GamerMorph, MorphDepthRunsFromTheCoarserDepthToTheTag) {
  // Depth d meets a 1 px target beyond errors[d] * 1000 m: 8000, 4000, 2000, 1000, 500 m.
  const float errors[] = {8.0f, 4.0f, 2.0f, 1.0f, 0.5f};
  EXPECT_FLOAT_EQ(morphDepthAt(errors, 2, 1000.0, 4000.0, 1.0f, 1.0f), 1.0f);  // depth 1 just fails
  EXPECT_FLOAT_EQ(morphDepthAt(errors, 2, 1000.0, 3000.0, 1.0f, 1.0f), 1.5f);
  EXPECT_FLOAT_EQ(morphDepthAt(errors, 2, 1000.0, 2000.0, 1.0f, 1.0f), 2.0f);  // depth 2 just meets it
  EXPECT_FLOAT_EQ(morphDepthAt(errors, 2, 1000.0, 3000.0, 1.0f, 0.5f), 2.0f);  // half the band: done
  EXPECT_FLOAT_EQ(morphDepthAt(errors, 2, 1000.0, 3500.0, 1.0f, 0.5f), 1.5f);
  EXPECT_FLOAT_EQ(morphDepthAt(errors, 2, 1000.0, 3000.0, 1.0f, 0.0f), 2.0f);  // no geomorph
  EXPECT_FLOAT_EQ(morphDepthAt(errors, 0, 1000.0, 9000.0, 1.0f, 1.0f), 0.0f);
  EXPECT_FLOAT_EQ(morphDepthAt(errors, 4, 1000.0, 100.0, 1.0f, 1.0f), 4.0f);  // past the finest
  // Depths 0 and 1 of equal error: beyond 4000 m the tag is 0, so tag 2 morphs from 0.
  const float tied[] = {4.0f, 4.0f, 2.0f, 1.0f, 0.5f};
  EXPECT_FLOAT_EQ(morphDepthAt(tied, 2, 1000.0, 4000.0, 1.0f, 1.0f), 0.0f);
  EXPECT_FLOAT_EQ(morphDepthAt(tied, 2, 1000.0, 3000.0, 1.0f, 1.0f), 1.0f);
  EXPECT_FLOAT_EQ(morphDepthAt(tied, 2, 1000.0, 2000.0, 1.0f, 1.0f), 2.0f);
}

// The refined surface of a whole small terrain (no culling) seen from a camera, evaluated at
// probe points between the lattice lines; `jumps` gets how far each probe moved since `last`.
class RefinedSurface {
 public:
  RefinedSurface(const CoarseTerrain& terrain, const PatternPool& pool) : terrain_(terrain), pool_(pool) {}

  // Selects for `camera` with `band`, checks that every point of the mesh has one height (no
  // crack), and returns the heights at the probes.
  std::vector<double> heights(const Camera& camera, float band, std::uint64_t& tagSum) {
    const HeightGrid& grid = terrain_.grid();
    const ViewSetup view = ViewSetup::create(camera, grid.worldBounds(), 640, 360);
    const LodView lodView = LodView::fromSetup(view, 1.0f);
    GamerSettings settings;
    settings.culling = false;
    settings.morphBand = band;
    settings.maxDepth = terrain_.maxDepth();
    DepthTags tags;
    terrain_.depthTags(lodView, settings.targetPx, band, tags);
    tagSum = 0;
    for (std::uint8_t t : tags.tag) tagSum += t;
    Selection selection;
    terrain_.select(lodView, settings, pool_, tags, selection);
    const std::vector<glm::vec3> mesh = terrain_.refinedMesh(pool_, selection);
    std::map<std::pair<float, float>, float> heightAt;
    for (const glm::vec3& v : mesh) {
      const auto [it, inserted] = heightAt.emplace(std::pair{v.x, v.y}, v.z);
      EXPECT_EQ(it->second, v.z) << "two heights at " << v.x << "," << v.y;
    }
    // Probes off every lattice line: (i + 0.37, j + 0.61) in grid units.
    const int side = grid.width - 1;
    std::vector<double> out(std::size_t(side) * std::size_t(side), std::nan(""));
    for (std::size_t t = 0; t + 2 < mesh.size(); t += 3) {
      const glm::dvec3 a = mesh[t], b = mesh[t + 1], c = mesh[t + 2];
      const double det = (b.x - a.x) * (c.y - a.y) - (c.x - a.x) * (b.y - a.y);
      const int x0 = int(std::floor(std::min({a.x, b.x, c.x}))), x1 = int(std::ceil(std::max({a.x, b.x, c.x})));
      const int y0 = int(std::floor(std::min({a.y, b.y, c.y}))), y1 = int(std::ceil(std::max({a.y, b.y, c.y})));
      for (int j = std::max(0, y0); j < std::min(side, y1); ++j) {
        for (int i = std::max(0, x0); i < std::min(side, x1); ++i) {
          const double px = i + 0.37, py = j + 0.61;
          const double u = ((px - a.x) * (c.y - a.y) - (c.x - a.x) * (py - a.y)) / det;
          const double v = ((b.x - a.x) * (py - a.y) - (px - a.x) * (b.y - a.y)) / det;
          if (u < 0.0 || v < 0.0 || u + v > 1.0) continue;
          out[std::size_t(j) * std::size_t(side) + std::size_t(i)] = a.z + u * (b.z - a.z) + v * (c.z - a.z);
        }
      }
    }
    for (double h : out) EXPECT_FALSE(std::isnan(h));  // the mesh covers the terrain
    return out;
  }

 private:
  const CoarseTerrain& terrain_;
  const PatternPool& pool_;
};

// How far the probes of the surface move in each of many small steps of the viewer.
struct SurfaceJumps {
  double largestM = 0.0;
  std::size_t overHalfMetre = 0;  // probe steps that moved more than 0.5 m
  int tagChanges = 0;             // steps in which some depth tag changed
};

// A viewer gliding low over a steep terrain in 2 m steps: many depth tags change on the way.
// Without the geomorph each pattern switch moves the surface by up to metres; with it the new
// vertices start on the coarser surface, so far fewer probes jump and by far less. (What is left
// are the bands between an edge still morphing and an interior whose pattern changes.)
TEST(GamerMorph, ASmallStepMovesTheSurfaceLittleAlthoughPatternsSwitch) {
  TerrainParams params;
  params.size = 129;
  params.seed = 7;
  params.spacingM = 30.0;
  params.reliefM = 1500.0;
  const HeightGrid grid = generateTerrain(params);
  Result<CoarseTerrain> terrain = CoarseTerrain::create(grid, 4);
  ASSERT_TRUE(terrain) << terrain.error().message;
  Result<PatternPool> pool = PatternPool::build(4);
  ASSERT_TRUE(pool);
  RefinedSurface surface(terrain.value(), pool.value());
  const auto glide = [&](float band) {
    Camera camera;
    camera.position = {200.0, 300.0, grid.heightAtWorld(200.0, 300.0) + 150.0};
    camera.yawDeg = 45.0;
    camera.pitchDeg = -20.0;
    SurfaceJumps jumps;
    std::uint64_t lastTags = 0, tags = 0;
    std::vector<double> last = surface.heights(camera, band, lastTags);
    for (int step = 0; step < 150; ++step) {
      camera.position += glm::dvec3(2.0, 2.0, 0.0) * (1.0 / std::sqrt(2.0));
      std::vector<double> now = surface.heights(camera, band, tags);
      jumps.tagChanges += tags != lastTags ? 1 : 0;
      lastTags = tags;
      for (std::size_t k = 0; k < now.size(); ++k) {
        const double jump = std::abs(now[k] - last[k]);
        jumps.largestM = std::max(jumps.largestM, jump);
        jumps.overHalfMetre += jump > 0.5 ? 1 : 0;
      }
      last = std::move(now);
    }
    return jumps;
  };
  const SurfaceJumps morphed = glide(1.0f), popping = glide(0.0f);
  EXPECT_GE(morphed.tagChanges, 5);                  // patterns switch on the way
  EXPECT_EQ(morphed.tagChanges, popping.tagChanges);  // the same tags: the geomorph moves heights only
  EXPECT_GT(popping.largestM, 2.0) << "whole levels should pop without the geomorph";
  EXPECT_LT(morphed.largestM, 0.5 * popping.largestM);
  EXPECT_LT(double(morphed.overHalfMetre), 0.25 * double(popping.overHalfMetre))
      << morphed.overHalfMetre << " against " << popping.overHalfMetre;
}

}  // namespace
}  // namespace tellus::gamer
