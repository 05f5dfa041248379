// RINGO's block meshes (seed 002): which edges abut a coarser ring, and crack-free joins: with
// its odd edge vertices collapsed, a finer block's edge consists of exactly its coarser
// neighbour's edge vertices, bit for bit, and blocks of one level share their edge vertices bit
// for bit.
#include <gtest/gtest.h>

#include <glm/geometric.hpp>

#include "ringo_test_heights.hpp"
#include "support/test_support.hpp"
#include "tellus/core/enu_frame.hpp"
#include "tellus/core/geodesy.hpp"
#include "tellus/lod/ringo/ringo_block_mesh.hpp"

namespace tellus {
namespace {

constexpr RingoLayout kLayout{.rings = 4, .tileCells = 16};
constexpr int kDepth = 10;

// Rough heights, so that an uncollapsed odd vertex is metres off the coarse edge.
std::vector<float> heightsOf(const RingoBlock& block) {
  return test::ringoTestHeights(block, kLayout, 500.0, 1009);
}

RingoBlockMesh meshAt(const RingoBlockMatrix& matrix, int dx, int dy) {
  const RingoBlock& block = matrix.at(dx, dy);
  return buildRingoBlockMesh(block, kLayout.cellsAt(block.level), heightsOf(block), nullptr);
}

// ECEF of vertex (i, j) as drawn with `coarserEdges`.
glm::dvec3 drawn(const RingoBlockMesh& mesh, int i, int j, std::uint32_t coarserEdges) {
  const RingoVertex& v = mesh.vertices[std::size_t(j) * std::size_t(mesh.cells + 1) + std::size_t(i)];
  return ringoVertexEcef(v, coarserEdges);
}

TEST(RingoBlockMesh, CoarserEdgesFollowTheRings) {
  const RingoLayout layout;
  EXPECT_EQ(ringoCoarserEdges(0, 0, layout), 0u);
  EXPECT_EQ(ringoCoarserEdges(1, 0, layout), std::uint32_t(kRingoEast));
  EXPECT_EQ(ringoCoarserEdges(1, 1, layout), std::uint32_t(kRingoEast | kRingoSouth));
  EXPECT_EQ(ringoCoarserEdges(-1, -1, layout), std::uint32_t(kRingoWest | kRingoNorth));
  EXPECT_EQ(ringoCoarserEdges(2, 0, layout), std::uint32_t(kRingoEast));
  EXPECT_EQ(ringoCoarserEdges(-3, 3, layout), std::uint32_t(kRingoWest | kRingoSouth));
  EXPECT_EQ(ringoCoarserEdges(5, 0, layout), 0u);  // the outer ring: nothing beyond
  EXPECT_EQ(ringoCoarserEdges(0, -5, layout), 0u);
}

TEST(RingoBlockMesh, AFinerBlocksEdgeIsItsCoarserNeighboursVertices) {
  const RingoBlockMatrix matrix(kLayout, kDepth, 900, 300);
  // (2, 0) is level 1; east of it (3, 0) is level 2.
  const RingoBlockMesh fine = meshAt(matrix, 2, 0), coarse = meshAt(matrix, 3, 0);
  ASSERT_EQ(fine.cells, 2 * coarse.cells);
  const std::uint32_t mask = ringoCoarserEdges(2, 0, matrix.layout());
  ASSERT_EQ(mask, std::uint32_t(kRingoEast));
  double worstUncollapsed = 0.0;
  for (int j = 0; j <= fine.cells; ++j) {
    // Row j of the fine east edge is drawn at the coarse west edge's vertex j / 2 (odd rows
    // collapse northwards onto the even one), the same bits.
    EXPECT_EQ(drawn(fine, fine.cells, j, mask), drawn(coarse, 0, j / 2, 0)) << "row " << j;
    if (j % 2 == 1) {
      const glm::dvec3 mid =
          0.5 * (drawn(coarse, 0, j / 2, 0) + drawn(coarse, 0, j / 2 + 1, 0));
      worstUncollapsed = std::max(worstUncollapsed, glm::distance(drawn(fine, fine.cells, j, 0), mid));
    }
  }
  EXPECT_GT(worstUncollapsed, 1.0) << "uncollapsed, the odd vertices would leave the coarse edge";
  // Its other edges stay where they are: the west neighbour (1, 0) is finer, not coarser.
  for (int j = 0; j <= fine.cells; ++j) {
    EXPECT_EQ(drawn(fine, 0, j, mask), drawn(fine, 0, j, 0));
  }
}

TEST(RingoBlockMesh, BlocksOfOneLevelShareTheirEdgeVertices) {
  const RingoBlockMatrix matrix(kLayout, kDepth, 900, 300);
  const RingoBlockMesh centre = meshAt(matrix, 0, 0), south = meshAt(matrix, 0, 1);
  for (int i = 0; i <= centre.cells; ++i) {
    EXPECT_EQ(drawn(centre, i, centre.cells, 0), drawn(south, i, 0, 0)) << i;
  }
  // Normals: unit, pointing away from the Earth's centre.
  for (const RingoVertex& v : centre.vertices) {
    const glm::vec3 n = unpackRingoNormal(v.normal);
    EXPECT_NEAR(glm::length(n), 1.0f, 0.01f);
    EXPECT_GT(glm::dot(glm::dvec3(n), glm::dvec3(v.whole)), 0.0);
  }
}

// Every vertex is its sample on the ellipsoid at H + N (the geoid's undulation there), to the
// split position's float fraction; normals face up (within 60 degrees of the ellipsoid's normal
// on these 500 m of rough relief).
TEST(RingoBlockMesh, VerticesAreTheSamplesAtTheirEllipsoidalHeight) {
  TELLUS_REQUIRE_SHARED_DATA(data);
  Result<Geoid> geoid = Geoid::load(data / "egm96-geoid/egm96_15.gtx");
  ASSERT_TRUE(geoid);
  const RingoBlockMatrix matrix(kLayout, kDepth, 900, 300);
  for (const auto& [dx, dy] : {std::pair{0, 0}, std::pair{3, -2}}) {
    const RingoBlock& block = matrix.at(dx, dy);
    const int cells = kLayout.cellsAt(block.level);
    const std::vector<float> heights = heightsOf(block);
    const RingoBlockMesh mesh = buildRingoBlockMesh(block, cells, heights, &geoid.value());
    const GeoBounds box = GlobalTiling::bounds(block.key);
    const double step = (box.eastDeg - box.westDeg) / cells;
    for (int j = 0; j <= cells; ++j) {
      for (int i = 0; i <= cells; ++i) {
        const double lat = box.northDeg - j * step, lon = box.westDeg + i * step;
        const std::size_t k = std::size_t(j) * std::size_t(cells + 1) + std::size_t(i);
        const glm::dvec3 expected = wgs84::geodeticToEcef(
            {lat * wgs84::kDegree, lon * wgs84::kDegree,
             heights[k] + geoid->undulationM(lat, lon)});
        ASSERT_LT(glm::distance(drawn(mesh, i, j, 0), expected), 1e-3) << i << ", " << j;
        const glm::dvec3 up = EnuAxes::at(lat * wgs84::kDegree, lon * wgs84::kDegree).up;
        EXPECT_GT(glm::dot(glm::dvec3(unpackRingoNormal(mesh.vertices[k].normal)), up), 0.5);
      }
    }
  }
}

}  // namespace
}  // namespace tellus
