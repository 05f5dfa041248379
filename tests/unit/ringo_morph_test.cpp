// RINGO's geomorph across a change of depth (lod/ringo/ringo_morph.hpp): a new matrix's blocks
// start on the surface the previous matrix drew (also when that one was itself mid-morph), end
// on their own, and stay crack-free in between: vertices that blocks share move together.
#include <cmath>
#include <map>
#include <utility>
#include <vector>

#include <gtest/gtest.h>
#include <glm/geometric.hpp>

#include "ringo_test_heights.hpp"
#include "tellus/core/geodesy.hpp"
#include "tellus/lod/ringo/ringo_block_mesh.hpp"
#include "tellus/lod/ringo/ringo_morph.hpp"

namespace tellus {
namespace {

constexpr RingoLayout kLayout{.rings = 4, .tileCells = 16};

// One matrix's blocks, built (morphing from `from`, if any), with what its successor needs.
struct BuiltMatrix {
  RingoBlockMatrix matrix;
  std::map<int, RingoBlockMesh> meshes;  // by slot
  std::map<int, std::vector<float>> heights;
};

BuiltMatrix build(int depth, std::int64_t centreX, int centreY, const RingoMorphSource* from) {
  BuiltMatrix built{RingoBlockMatrix(kLayout, depth, centreX, centreY), {}, {}};
  for (int slot = 0; slot < built.matrix.slotCount(); ++slot) {
    const RingoBlock& block = built.matrix.slot(slot);
    if (!block.exists) continue;
    // Rough heights, a different surface at every depth (as a finer store depth is).
    built.heights[slot] = test::ringoTestHeights(block, kLayout, 300.0 * depth, 997);
    built.meshes[slot] = buildRingoBlockMesh(block, kLayout.cellsAt(block.level),
                                             built.heights[slot], nullptr, from);
  }
  return built;
}

// What `built` draws at `remaining` morph, as a source for its successor.
std::shared_ptr<RingoMorphSource> capture(const BuiltMatrix& built, float remaining) {
  auto source = std::make_shared<RingoMorphSource>(built.matrix.depth(), remaining);
  for (const auto& [slot, mesh] : built.meshes) {
    source->add(built.matrix.slot(slot).key,
                {mesh.cells, std::make_shared<const std::vector<float>>(built.heights.at(slot)),
                 mesh.morphDeltasM.empty()
                     ? nullptr
                     : std::make_shared<const std::vector<float>>(mesh.morphDeltasM)});
  }
  return source;
}

// A vertex's place as a key: its latitude and longitude (to 1e-9 degrees).
std::pair<std::int64_t, std::int64_t> placeOf(const glm::dvec3& ecef) {
  const wgs84::Geodetic g = wgs84::ecefToGeodetic(ecef);
  return {std::llround(g.latRad / wgs84::kDegree * 1e9), std::llround(g.lonRad / wgs84::kDegree * 1e9)};
}

// Where `built` draws each of its vertices at `remaining`, by place.
std::map<std::pair<std::int64_t, std::int64_t>, glm::dvec3> drawnVertices(const BuiltMatrix& built,
                                                                           float remaining) {
  std::map<std::pair<std::int64_t, std::int64_t>, glm::dvec3> drawn;
  for (const auto& [slot, mesh] : built.meshes) {
    for (const RingoVertex& v : mesh.vertices) {
      drawn[placeOf(ringoVertexEcef(v, 0, 0.0f))] = ringoVertexEcef(v, 0, remaining);
    }
  }
  return drawn;
}

// The largest distance between where `next` draws its vertices at the start of its morph and
// where `before` drew the same places at `beforeRemaining`; `matched` counts the places.
double startGap(const BuiltMatrix& next, const BuiltMatrix& before, float beforeRemaining,
                int& matched) {
  const auto old = drawnVertices(before, beforeRemaining);
  double worst = 0.0;
  matched = 0;
  for (const auto& [slot, mesh] : next.meshes) {
    for (const RingoVertex& v : mesh.vertices) {
      const auto it = old.find(placeOf(ringoVertexEcef(v, 0, 0.0f)));
      if (it == old.end()) continue;
      ++matched;
      worst = std::max(worst, glm::distance(ringoVertexEcef(v, 0, 1.0f), it->second));
    }
  }
  return worst;
}

TEST(RingoMorph, ANewDepthStartsOnTheSurfaceDrawnBeforeAndEndsOnItsOwn) {
  const BuiltMatrix coarse = build(10, 900, 300, nullptr);
  const std::shared_ptr<RingoMorphSource> fromCoarse = capture(coarse, 0.0f);
  const BuiltMatrix finer = build(11, 1800, 600, fromCoarse.get());
  int matched = 0;
  // Within millimetres: the delta is a float, and the vertex moves along the normal of the
  // ellipsoid scaled through it (as ringo.vert does), a hair off the geodetic normal.
  EXPECT_LT(startGap(finer, coarse, 0.0f, matched), 0.01);
  EXPECT_GT(matched, 500);
  // Morphed, a vertex is its own sample: the surfaces differ by hundreds of metres.
  double moved = 0.0;
  for (const auto& [slot, mesh] : finer.meshes) {
    for (const RingoVertex& v : mesh.vertices) {
      EXPECT_EQ(ringoVertexEcef(v, 0, 0.0f),
                glm::dvec3(v.whole) + glm::dvec3(v.fraction));
      moved = std::max(moved, glm::distance(ringoVertexEcef(v, 0, 1.0f), ringoVertexEcef(v, 0, 0.0f)));
    }
  }
  EXPECT_GT(moved, 100.0);
}

// A depth change during a morph: the next matrix starts where the interrupted one stopped.
TEST(RingoMorph, AMorphInterruptedByTheNextDepthHandsOnItsSurface) {
  const BuiltMatrix coarse = build(10, 900, 300, nullptr);
  const BuiltMatrix middle = build(11, 1800, 600, capture(coarse, 0.0f).get());
  const BuiltMatrix fine = build(12, 3600, 1200, capture(middle, 0.4f).get());
  int matched = 0;
  EXPECT_LT(startGap(fine, middle, 0.4f, matched), 0.01);
  EXPECT_GT(matched, 500);
  // Without the middle matrix's own morph share the start would be off by metres.
  int unused = 0;
  EXPECT_GT(startGap(fine, middle, 0.0f, unused), 1.0);
}

TEST(RingoMorph, VerticesThatBlocksShareMoveTogether) {
  const BuiltMatrix coarse = build(10, 900, 300, nullptr);
  const BuiltMatrix finer = build(11, 1800, 600, capture(coarse, 0.0f).get());
  const RingoBlockMatrix& m = finer.matrix;
  const auto mesh = [&](int dx, int dy) -> const RingoBlockMesh& {
    return finer.meshes.at(m.slotAt(dx, dy));
  };
  const auto at = [](const RingoBlockMesh& block, int i, int j, std::uint32_t mask, float remaining) {
    return ringoVertexEcef(
        block.vertices[std::size_t(j) * std::size_t(block.cells + 1) + std::size_t(i)], mask,
        remaining);
  };
  for (const float remaining : {1.0f, 0.63f, 0.37f, 0.0f}) {
    // (2, 0) is level 1 with the coarser (3, 0) east of it: its collapsed edge is (3, 0)'s.
    const RingoBlockMesh& fine = mesh(2, 0);
    const RingoBlockMesh& coarser = mesh(3, 0);
    const std::uint32_t mask = ringoCoarserEdges(2, 0, kLayout);
    for (int j = 0; j <= fine.cells; ++j) {
      EXPECT_EQ(at(fine, fine.cells, j, mask, remaining), at(coarser, 0, j / 2, 0, remaining))
          << "row " << j << " at " << remaining;
    }
    // Blocks of one level: the centre and the one south of it.
    const RingoBlockMesh& centre = mesh(0, 0);
    const RingoBlockMesh& south = mesh(0, 1);
    for (int i = 0; i <= centre.cells; ++i) {
      EXPECT_EQ(at(centre, i, centre.cells, 0, remaining), at(south, i, 0, 0, remaining)) << i;
    }
  }
}

TEST(RingoMorph, AMorphTakesItsFramesOrKeepsUpWithTheViewersHeight) {
  // Hovering: 1 / 8 a frame, done on the 8th frame.
  float remaining = 1.0f;
  int frames = 0;
  while (remaining > 0.0f && frames < 100) {
    remaining = ringoMorphStep(remaining, 8, 0.0);
    ++frames;
  }
  EXPECT_EQ(frames, 8);
  // A slow descent (a hundredth of a depth a frame) takes the same frames.
  EXPECT_FLOAT_EQ(ringoMorphStep(1.0f, 8, 0.01), 0.875f);
  // A time-lapse moving a tenth of a depth a frame is done in 3 frames: 0.6, 0.2, 0.
  EXPECT_NEAR(ringoMorphStep(1.0f, 8, 0.1), 0.6f, 1e-6f);
  EXPECT_FLOAT_EQ(ringoMorphStep(0.2f, 8, 0.1), 0.0f);
  // Climbing counts as descending does; 0 frames is no morph.
  EXPECT_NEAR(ringoMorphStep(1.0f, 8, -0.1), 0.6f, 1e-6f);
  EXPECT_FLOAT_EQ(ringoMorphStep(1.0f, 0, 0.0), 0.0f);
}

// A block's vertices take their deltas from the lattice form: the same bits as point by point,
// across old tiles' borders and where the old surface ends.
TEST(RingoMorph, TheLatticeIsThePointwiseSurface) {
  const BuiltMatrix coarse = build(10, 900, 300, nullptr);
  const std::shared_ptr<RingoMorphSource> source = capture(build(11, 1800, 600, capture(coarse, 0.0f).get()), 0.3f);
  const GeoBounds box = GlobalTiling::bounds({11, 1800, 600});
  std::vector<double> lat, lon;
  // Six tiles' width each way (the matrix reaches five and a half), 97 points.
  for (int k = 0; k <= 96; ++k) {
    lat.push_back(box.northDeg + (3.0 - k / 16.0) * (box.northDeg - box.southDeg) * 2.0);
    lon.push_back(box.westDeg + (-3.0 + k / 16.0) * (box.eastDeg - box.westDeg) * 2.0);
  }
  std::vector<double> lattice(lat.size() * lon.size());
  source->heightsOnLattice(lat, lon, lattice);
  int finite = 0, missing = 0;
  for (std::size_t j = 0; j < lat.size(); ++j) {
    for (std::size_t i = 0; i < lon.size(); ++i) {
      const double point = source->heightAt(lat[j], lon[i]);
      const double fromLattice = lattice[j * lon.size() + i];
      if (std::isnan(point)) {
        EXPECT_TRUE(std::isnan(fromLattice));
        ++missing;
        continue;
      }
      EXPECT_EQ(fromLattice, point) << j << ", " << i;
      ++finite;
    }
  }
  EXPECT_GT(finite, 4000);
  EXPECT_GT(missing, 100);  // beyond the depth-11 matrix
}

TEST(RingoMorph, NoBlockNoDelta) {
  const RingoMorphSource none(10, 1.0f);
  EXPECT_TRUE(std::isnan(none.heightAt(42.0, 12.0)));
  const RingoBlockMatrix matrix(kLayout, 11, 1800, 600);
  const RingoBlock& block = matrix.at(0, 0);
  const RingoBlockMesh mesh = buildRingoBlockMesh(
      block, kLayout.cellsAt(block.level), test::ringoTestHeights(block, kLayout, 100.0, 50),
      nullptr, &none);
  EXPECT_TRUE(mesh.morphDeltasM.empty());  // an empty source: no morph
}

}  // namespace
}  // namespace tellus
