// Geometry clipmaps' GL-free parts (seed 004 section 2.3): the footprints tile every level's
// ring exactly once and leave exactly the finer level's square, the levels nest around the
// viewer, the toroidal update leaves a level's texture equal to a fresh fill after any moves,
// and the geomorph reaches the coarser level's surface at every level's border.
#include <map>
#include <random>
#include <vector>

#include <gtest/gtest.h>
#include <glm/common.hpp>

#include "tellus/lod/clipmaps/clipmap_heights.hpp"
#include "tellus/lod/clipmaps/clipmap_layout.hpp"
#include "tellus/lod/clipmaps/clipmap_update.hpp"

namespace tellus::clipmaps {
namespace {

// A deterministic, non-linear height for every (level, sample), pyramid-consistent: level l's
// sample (i, j) is level 0's sample (i * 2^l, j * 2^l).
float testHeight(int level, glm::ivec2 s) {
  const long long x = static_cast<long long>(s.x) << level, y = static_cast<long long>(s.y) << level;
  return float((x * 7919 + y * 104729) % 1000) * 0.5f + float((x * y) % 97);
}

ClipmapShape shapeOf(int n, int levels) {
  Result<ClipmapShape> shape = ClipmapShape::create(n, levels);
  EXPECT_TRUE(shape);
  return shape.value();
}

// Coverage of each cell's two halves (SW-NE split) by the pieces of one level.
std::map<std::pair<int, int>, std::array<int, 2>> coverage(const Footprints& f, const ClipmapShape& shape,
                                                           const std::vector<const Piece*>& pieces) {
  std::map<std::pair<int, int>, std::array<int, 2>> cells;
  for (const Piece* piece : pieces) {
    for (std::uint32_t i = 0; i < piece->indexCount; i += 3) {
      glm::ivec2 v[3];
      for (int k = 0; k < 3; ++k) {
        const std::uint32_t id = f.indices[piece->firstIndex + i + std::uint32_t(k)];
        v[k] = {int(id) % shape.n, int(id) / shape.n};
      }
      const int area2 = (v[1].x - v[0].x) * (v[2].y - v[0].y) - (v[1].y - v[0].y) * (v[2].x - v[0].x);
      if (piece->kind == PieceKind::Degenerate) {
        EXPECT_EQ(area2, 0);
        continue;
      }
      // Counter-clockwise seen from above is clockwise in (col, row), rows running south.
      EXPECT_EQ(area2, -1);
      const glm::ivec2 lo = glm::min(glm::min(v[0], v[1]), v[2]);
      // The half holding the SE corner (x + 1, y + 1) or the NW corner (x, y).
      bool southEast = false;
      for (const glm::ivec2& p : v) southEast |= p == lo + 1;
      ++cells[{lo.x, lo.y}][southEast ? 0 : 1];
    }
  }
  return cells;
}

TEST(ClipmapLayout, FootprintsCoverEachRingOnceAroundTheFinerLevel) {
  for (const int n : {31, 63, 255}) {
    const ClipmapShape shape = shapeOf(n, 3);
    const Footprints f = buildFootprints(shape);
    const int m = shape.m;
    // The finest level: the whole square, once.
    const auto finest = coverage(f, shape, piecesForLevel(f, shape, 0, {0, 0}));
    EXPECT_EQ(finest.size(), std::size_t((n - 1) * (n - 1)));
    for (const auto& [cell, halves] : finest) EXPECT_EQ(halves, (std::array<int, 2>{1, 1}));
    for (int ty = 0; ty < 2; ++ty) {
      for (int tx = 0; tx < 2; ++tx) {
        const auto cells = coverage(f, shape, piecesForLevel(f, shape, 1, {tx, ty}));
        // The finer level's square, in this level's cells: 2m - 1 a side from m - 1 + t.
        const glm::ivec2 finerMin(m - 1 + tx, m - 1 + ty), finerMax = finerMin + (2 * m - 1);
        for (int y = 0; y < n - 1; ++y) {
          for (int x = 0; x < n - 1; ++x) {
            const bool finer = x >= finerMin.x && x < finerMax.x && y >= finerMin.y && y < finerMax.y;
            const auto found = cells.find({x, y});
            if (finer) {
              EXPECT_TRUE(found == cells.end()) << "n " << n << " cell " << x << "," << y;
            } else {
              ASSERT_TRUE(found != cells.end()) << "n " << n << " gap at " << x << "," << y;
              EXPECT_EQ(found->second, (std::array<int, 2>{1, 1})) << "n " << n << " cell " << x << "," << y;
            }
          }
        }
      }
    }
    // Degenerate triangles at the border of all but the coarsest level.
    bool degenerate = false;
    for (const Piece* p : piecesForLevel(f, shape, 2, {0, 0})) degenerate |= p->kind == PieceKind::Degenerate;
    EXPECT_FALSE(degenerate);
  }
}

TEST(ClipmapLayout, LevelsNestAroundTheViewer) {
  const ClipmapShape shape = shapeOf(63, 6);
  std::mt19937 random(3);
  std::uniform_real_distribution<double> coordinate(-3000.0, 9000.0);
  for (int trial = 0; trial < 500; ++trial) {
    const glm::dvec2 viewer(coordinate(random), coordinate(random));
    const std::vector<glm::ivec2> origins = placeLevels(shape, viewer);
    for (int level = 0; level < shape.levels; ++level) {
      const glm::dvec2 centre = glm::dvec2(origins[std::size_t(level)] + (shape.n - 1) / 2);
      const glm::dvec2 v = viewer / std::ldexp(1.0, level);
      EXPECT_LE(std::abs(centre.x - v.x), 1.0);
      EXPECT_LE(std::abs(centre.y - v.y), 1.0);
      if (level > 0) {
        const glm::ivec2 t = trimSide(shape, origins[std::size_t(level)], origins[std::size_t(level - 1)]);
        EXPECT_TRUE(t.x == 0 || t.x == 1);
        EXPECT_TRUE(t.y == 0 || t.y == 1);
        EXPECT_EQ(origins[std::size_t(level - 1)].x % 2, 0);
      }
    }
  }
}

// Sizes 2^k - 1 (texture 32) and 4m - 1 that is not (texture 36): the wrap is a modulo either way.
TEST(ClipmapLayout, ToroidalUpdatesEqualAFreshFillAfterRandomMoves) {
  for (const int n : {31, 35}) {
    const ClipmapShape shape = shapeOf(n, 4);
    const int size = shape.textureSize;
    const int level = 2;
    std::vector<float> texture(std::size_t(size * size), -1.0f);
    const auto fill = [&](const SampleRect& rect) {
      for (const ToroidalPiece& piece : wrapToroidally(rect, size)) {
        const glm::ivec2 extent = piece.samples.max - piece.samples.min;
        EXPECT_LE(piece.texel.x + extent.x, size);
        EXPECT_LE(piece.texel.y + extent.y, size);
        for (int y = 0; y < extent.y; ++y) {
          for (int x = 0; x < extent.x; ++x) {
            texture[std::size_t((piece.texel.y + y) * size + piece.texel.x + x)] =
                testHeight(level, piece.samples.min + glm::ivec2(x, y));
          }
        }
      }
    };
    glm::ivec2 origin(-40, 17);
    fill({origin, origin + shape.n});
    std::mt19937 random(9);
    std::uniform_int_distribution<int> step(-9, 9), jump(-100, 100);
    for (int move = 0; move < 300; ++move) {
      const glm::ivec2 next = origin + (move % 50 == 49 ? glm::ivec2(jump(random), jump(random))
                                                        : glm::ivec2(step(random), step(random)));
      std::uint64_t updated = 0;
      for (const SampleRect& rect : exposedRegions(shape, origin, next)) {
        fill(rect);
        updated += std::uint64_t((rect.max - rect.min).x) * std::uint64_t((rect.max - rect.min).y);
      }
      const glm::ivec2 d = glm::abs(next - origin);
      if (d.x < shape.n && d.y < shape.n) {  // only the L the window gained
        EXPECT_EQ(updated, std::uint64_t(d.x * shape.n + d.y * (shape.n - d.x)));
      }
      origin = next;
      for (int y = 0; y < shape.n; ++y) {
        for (int x = 0; x < shape.n; ++x) {
          const glm::ivec2 s = origin + glm::ivec2(x, y);
          const glm::ivec2 texel = toroidalTexel(s, size);
          ASSERT_EQ(texture[std::size_t(texel.y * size + texel.x)], testHeight(level, s))
              << "move " << move << " sample " << s.x << "," << s.y;
        }
      }
    }
  }
}

TEST(ClipmapHeights, TheBorderOfEveryLevelLiesOnTheCoarserSurface) {
  const ClipmapShape shape = shapeOf(63, 5);
  const LevelSampler sampler = testHeight;
  std::mt19937 random(4);
  std::uniform_real_distribution<double> coordinate(0.0, 2000.0);
  for (int trial = 0; trial < 40; ++trial) {
    const glm::dvec2 viewer(coordinate(random), coordinate(random));
    const std::vector<glm::ivec2> origins = placeLevels(shape, viewer);
    for (int level = 0; level + 1 < shape.levels; ++level) {
      const glm::dvec2 v = viewer / std::ldexp(1.0, level);
      const glm::ivec2 o = origins[std::size_t(level)];
      for (int i = 0; i < shape.n; ++i) {
        for (const glm::ivec2 local : {glm::ivec2(i, 0), glm::ivec2(i, shape.n - 1), glm::ivec2(0, i),
                                       glm::ivec2(shape.n - 1, i)}) {
          EXPECT_EQ(blendWeight(shape, o + local, v), 1.0f);
        }
      }
      // The coarser level's own vertices around its hole are not blended.
      const glm::ivec2 coarse = origins[std::size_t(level + 1)];
      const glm::dvec2 cv = viewer / std::ldexp(1.0, level + 1);
      for (int i = shape.m - 1; i <= 3 * shape.m - 1; ++i) {
        EXPECT_EQ(blendWeight(shape, coarse + glm::ivec2(i, shape.m - 1), cv), 0.0f);
      }
    }
  }
  // z_c follows the coarser triangulation: on a plane it is the plane, at a coarse cell's centre
  // the mean of its SW-NE diagonal.
  const LevelSampler plane = [](int level, glm::ivec2 s) {
    return float((s.x << level) * 3 - (s.y << level) * 2 + 100);
  };
  EXPECT_EQ(coarserSurfaceHeight(plane, 1, {5, 7}), plane(1, {5, 7}));
  EXPECT_EQ(coarserSurfaceHeight(plane, 0, {-3, 4}), plane(0, {-3, 4}));
  EXPECT_EQ(coarserSurfaceHeight(sampler, 1, {5, 7}),
            0.5f * (sampler(2, {2, 4}) + sampler(2, {3, 3})));
}

TEST(ClipmapLayout, RefusesShapesThatAreNot4mMinusOne) {
  EXPECT_FALSE(ClipmapShape::create(256, 4));
  EXPECT_FALSE(ClipmapShape::create(301, 4));
  EXPECT_TRUE(ClipmapShape::create(303, 4));  // 4m - 1 with m = 76: not 2^k - 1
  EXPECT_FALSE(ClipmapShape::create(7, 4));
  EXPECT_FALSE(ClipmapShape::create(15, 4));  // no room for a transition band
  EXPECT_FALSE(ClipmapShape::create(255, 0));
  EXPECT_TRUE(ClipmapShape::create(127, 8));
  EXPECT_EQ(ClipmapShape::levelsFor(255, 4801, 4801), 7);
}

}  // namespace
}  // namespace tellus::clipmaps

namespace tellus::clipmaps {
namespace {

// The worker's update (clipmap_update.hpp): applied to a CPU copy of the toroidal texture array,
// every level's window holds texelHeights() of its samples after any moves, and a move that
// keeps a level's window sends nothing for it.
TEST(ClipmapUpdate, UpdatesLeaveEveryLevelEqualToAFreshFill) {
  // The store's levels, prefiltered ones, prefiltered ones clamped to a range the test heights
  // leave, and prefiltered ones on a terrain whose edge the windows cross (stored samples
  // there): the update's blocks give the per-sample definition's heights bit for bit.
  for (const LevelFilter& filter : {LevelFilter{false}, LevelFilter{true}, LevelFilter{true, 50.0f, 450.0f},
                                    LevelFilter{true, -1e9f, 1e9f, glm::ivec2(430, 330)}}) {
    const LevelSampler filtered = filteredSampler(testHeight, filter);
    const ClipmapShape shape = shapeOf(31, 4);
    const int size = shape.textureSize;
    std::vector<glm::vec2> texels(std::size_t(size) * std::size_t(size) * std::size_t(shape.levels));
    const auto apply = [&](const ClipmapUpdate& update) {
      for (const TexelRect& rect : update.rects) {
        ASSERT_EQ(rect.texels.size(), std::size_t(rect.size.x) * std::size_t(rect.size.y));
        for (int y = 0; y < rect.size.y; ++y) {
          for (int x = 0; x < rect.size.x; ++x) {
            texels[(std::size_t(rect.level) * std::size_t(size) + std::size_t(rect.texel.y + y)) * std::size_t(size) +
                   std::size_t(rect.texel.x + x)] = rect.texels[std::size_t(y * rect.size.x + x)];
          }
        }
      }
    };
    glm::dvec2 viewer(400.0, 300.0);
    ClipmapUpdate held = buildClipmapUpdate(shape, nullptr, viewer, testHeight, filter);
    EXPECT_EQ(held.samples, std::uint64_t(shape.n) * shape.n * std::uint64_t(shape.levels));
    apply(held);
    std::mt19937 random(12);
    std::uniform_real_distribution<double> step(-12.0, 12.0);
    for (int move = 0; move < 60; ++move) {
      viewer += glm::dvec2(step(random), step(random));
      const ClipmapUpdate update = buildClipmapUpdate(shape, &held.origins, viewer, testHeight, filter);
      EXPECT_EQ(update.origins, placeLevels(shape, viewer));
      EXPECT_EQ(update.viewer, viewer);
      if (update.origins == held.origins) {
        EXPECT_TRUE(update.rects.empty());
      }
      apply(update);
      held = update;
      for (int level = 0; level < shape.levels; ++level) {
        for (int y = 0; y < shape.n; ++y) {
          for (int x = 0; x < shape.n; ++x) {
            const glm::ivec2 s = held.origins[std::size_t(level)] + glm::ivec2(x, y);
            const glm::ivec2 t = toroidalTexel(s, size);
            ASSERT_EQ(texels[(std::size_t(level) * std::size_t(size) + std::size_t(t.y)) * std::size_t(size) + std::size_t(t.x)],
                      texelHeights(filtered, shape, level, s))
                << "move " << move << " level " << level;
          }
        }
      }
    }
  }
}

}  // namespace
}  // namespace tellus::clipmaps
