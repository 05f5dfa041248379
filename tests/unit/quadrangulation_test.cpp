// The quadrangulation pipeline's CPU reference (stacks/quadrangulation.hpp): the density rules,
// the smoothing taps, the cell classification against a brute-force rule for all 256 cases, and
// meshes that are closed, consistently oriented and of the right topology (a block, an arch).
#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <functional>
#include <set>

#include "support/stack_fixtures.hpp"
#include "tellus/formats/stacks/dual_contouring.hpp"
#include "tellus/formats/stacks/quadrangulation.hpp"
#include "tellus/formats/stacks/stack_generator.hpp"
#include "tellus/formats/stacks/stack_mesh_check.hpp"

namespace tellus {
namespace {

// Stacks of w x h columns from a function (x, row) -> layers, spacing 1 m, cells of 1 m.
QuantisedStacks stacksOf(int w, int h,
                         const std::function<std::vector<StackLayer>(int, int)>& column,
                         double cellM = 1.0) {
  std::vector<std::vector<StackLayer>> columns;
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) columns.push_back(column(x, y));
  }
  Result<StackTerrain> terrain = StackTerrain::fromColumns(w, h, 1.0, columns);
  EXPECT_TRUE(terrain) << terrain.error().message;
  Result<QuantisedStacks> q = QuantisedStacks::from(terrain.value(), cellM);
  EXPECT_TRUE(q) << q.error().message;
  return q.value();
}

StackMesh wholeTerrain(const QuantisedStacks& stacks, const QuadParams& params) {
  return quadrangulateNodes(stacks, params, nodesWithSurface(stacks, params));
}

TEST(Quadrangulation, DensityFollowsTheSeedsRules) {
  // One column: rock [0.25, 1.5), soil [1.5, 2.75) (two layers share cell 1: they add up),
  // grass [4.25, 4.75) (first cell == last cell: e - s).
  const QuantisedStacks stacks = stacksOf(1, 1, [](int, int) {
    return std::vector<StackLayer>{{0.25f, 1.5f, 1}, {1.5f, 2.75f, 2}, {4.25f, 4.75f, 3}};
  });
  QuadParams params;
  params.filterRadius = 0;
  params.nodeCells = 8;
  const DensityVolume raw = densityStage(stacks, params, {-1, -1, -1});
  const int shift = 1;  // raw sample 0 is node-local -1, and the node's origin is -1
  const auto at = [&](int cell) { return raw.samples[raw.index(2, 2, cell + 2)]; };
  (void)shift;
  EXPECT_EQ(at(0), (DensitySample{192, 0, 0, 0}));  // 1 - frac(0.25)
  EXPECT_EQ(at(1), (DensitySample{128, 128, 0, 0}));
  EXPECT_EQ(at(2), (DensitySample{0, 192, 0, 0}));  // frac(2.75)
  EXPECT_EQ(at(3), (DensitySample{0, 0, 0, 0}));
  EXPECT_EQ(at(4), (DensitySample{0, 0, 128, 0}));  // 4.75 - 4.25
  EXPECT_EQ(at(-1), (DensitySample{0, 0, 0, 0}));   // below the base: air
  // A neighbouring column outside the terrain is air.
  EXPECT_EQ(raw.samples[raw.index(1, 2, 2)], (DensitySample{0, 0, 0, 0}));
}

TEST(Quadrangulation, SurfaceLayersAreAtLeastOneCellThickAndGeometryIsKept) {
  // Cells of 2 m. The ground: rock to 10 m, soil to 11.5 m, grass to 11.75 m. A thin deck: rock
  // 14..15 m under grass to 15.25 m. A thick one over air: moss (material 4) 30..30.5 m under
  // rock to 40 m.
  const QuantisedStacks stacks = stacksOf(1, 1, [](int, int) {
    return std::vector<StackLayer>{{0.0f, 10.0f, 1},  {10.0f, 11.5f, 2}, {11.5f, 11.75f, 3},
                                   {14.0f, 15.0f, 1}, {15.0f, 15.25f, 3}, {30.0f, 30.5f, 4},
                                   {30.5f, 40.0f, 1}};
  }, 2.0);
  const auto units = [](double metres) { return std::int32_t(metres / 2.0 * kSubCell); };
  struct Expected {
    double bottom, top;
    std::uint32_t channel;
  };
  const std::vector<Expected> expected{
      {0.0, 9.75, 0},    // rock, cut to leave the top cell to the surface
      {9.75, 11.75, 2},  // grass: one cell under the ground's top (the soil under it is gone)
      {14.0, 15.25, 2},  // the thin deck: the top wins, all grass
      {30.0, 32.0, 3},   // the ceiling's moss: one cell over the air under it
      {32.0, 40.0, 0},   // rock above it
  };
  const auto column = stacks.column(0, 0);
  ASSERT_EQ(column.size(), expected.size());
  for (std::size_t i = 0; i < expected.size(); ++i) {
    EXPECT_EQ(column[i].bottom, units(expected[i].bottom)) << i;
    EXPECT_EQ(column[i].top, units(expected[i].top)) << i;
    EXPECT_EQ(column[i].channel, expected[i].channel) << i;
  }
}

TEST(Quadrangulation, SmoothingTapsAreBinomialOrBox) {
  QuadParams gauss;
  gauss.filterRadius = 2;
  EXPECT_EQ(gauss.filterTaps(), (std::vector<std::uint32_t>{1, 4, 6, 4, 1}));
  EXPECT_EQ(gauss.filterNorm(), 16u * 16u * 16u);
  QuadParams box = gauss;
  box.filter = SmoothingFilter::Box;
  EXPECT_EQ(box.filterTaps(), (std::vector<std::uint32_t>{1, 1, 1, 1, 1}));
  EXPECT_EQ(box.filterNorm(), 125u);
  QuadParams bad;
  bad.nodeCells = 2;
  EXPECT_FALSE(bad.check());
  bad = QuadParams{};
  bad.filterRadius = 9;
  EXPECT_FALSE(bad.check());
}

TEST(Quadrangulation, SmoothingSpreadsAnImpulseAsTheTapsProduct) {
  QuadParams params;
  params.nodeCells = 3;
  params.filterRadius = 1;
  const int side = params.rawSide();
  DensityVolume raw{side, side, side, std::vector<DensitySample>(std::size_t(side * side * side))};
  const int c = side / 2;
  raw.samples[raw.index(c, c, c)] = {256, 0, 0, 0};
  const DensityVolume smoothed = smoothStage(raw, params);
  ASSERT_EQ(smoothed.sizeX, params.smoothSide());
  const int s = c - 1;  // the impulse in smoothed coordinates
  EXPECT_EQ(smoothed.samples[smoothed.index(s, s, s)][0], 256u * 8u);
  EXPECT_EQ(smoothed.samples[smoothed.index(s + 1, s, s)][0], 256u * 4u);
  EXPECT_EQ(smoothed.samples[smoothed.index(s + 1, s - 1, s + 1)][0], 256u);
  EXPECT_EQ(smoothed.samples[smoothed.index(s + 2, s, s)][0], 0u);
}

// The brute-force rule: corners are points of the unit cube; an edge is a pair of corners one
// unit apart; it crosses the surface when one end is inside. A cell has a vertex when any edge
// crosses; it owns the crossing edges at the origin; the quad faces the outside end.
TEST(Quadrangulation, ClassificationTableMatchesBruteForceForAll256Cases) {
  const auto position = [](int c) { return std::array<int, 3>{c & 1, (c >> 1) & 1, (c >> 2) & 1}; };
  // The edge table is every pair of corners one unit apart.
  int edges = 0;
  for (int a = 0; a < 8; ++a) {
    for (int b = a + 1; b < 8; ++b) {
      const auto pa = position(a), pb = position(b);
      const int distance = std::abs(pa[0] - pb[0]) + std::abs(pa[1] - pb[1]) + std::abs(pa[2] - pb[2]);
      if (distance != 1) continue;
      ++edges;
      bool listed = false;
      for (const auto& e : dc::kCellEdges) listed |= (e[0] == a && e[1] == b);
      EXPECT_TRUE(listed) << a << "-" << b;
    }
  }
  EXPECT_EQ(edges, 12);
  for (unsigned c = 0; c < 256; ++c) {
    bool anyCrossing = false;
    unsigned owned = 0;
    for (int a = 0; a < 8; ++a) {
      for (int b = a + 1; b < 8; ++b) {
        const auto pa = position(a), pb = position(b);
        if (std::abs(pa[0] - pb[0]) + std::abs(pa[1] - pb[1]) + std::abs(pa[2] - pb[2]) != 1) continue;
        const bool crosses = (((c >> a) & 1u) != 0) != (((c >> b) & 1u) != 0);
        anyCrossing |= crosses;
        if (crosses && a == 0) {
          const int axis = pb[0] ? 0 : pb[1] ? 1 : 2;
          owned |= 1u << axis;
        }
      }
    }
    EXPECT_EQ(dc::cellHasVertex(c), anyCrossing) << c;
    EXPECT_EQ(dc::crossingAxes(c), owned) << c;
    // Inside the node the cell owns all of them; in its first layers along the other axes, none.
    EXPECT_EQ(dc::ownedQuads(c, 1, 1, 1, 4), owned) << c;
    EXPECT_EQ(dc::ownedQuads(c, 0, 0, 0, 4), 0u) << c;
    EXPECT_EQ(dc::ownedQuads(c, 3, 3, 3, 4), 0u) << c;
  }
  // The quad's cells are the four around the edge, counter-clockwise about the axis.
  for (int axis = 0; axis < 3; ++axis) {
    const auto& cells = dc::kQuadCells[std::size_t(axis)];
    const int u = (axis + 1) % 3, v = (axis + 2) % 3;
    int area2 = 0;
    for (int q = 0; q < 4; ++q) {
      const auto& p = cells[std::size_t(q)];
      const auto& n = cells[std::size_t((q + 1) % 4)];
      EXPECT_EQ(p[std::size_t(axis)], 0);
      area2 += p[std::size_t(u)] * n[std::size_t(v)] - n[std::size_t(u)] * p[std::size_t(v)];
    }
    EXPECT_EQ(area2, 2) << "axis " << axis;  // positive: counter-clockwise
  }
}

TEST(Quadrangulation, FlatGroundIsAClosedLevelSurfaceFacingUp) {
  // 20 x 12 stacks of rock to 6.5 m, nodes of 5 cells (many nodes, shared cells welded).
  const QuantisedStacks stacks =
      stacksOf(20, 12, [](int, int) { return std::vector<StackLayer>{{0.0f, 6.5f, 1}}; });
  QuadParams params;
  params.nodeCells = 5;
  const StackMesh mesh = wholeTerrain(stacks, params);
  const StackMeshCheck check = checkStackMesh(mesh);
  EXPECT_TRUE(check.watertight()) << check.unbalancedEdges << " unbalanced edges";
  EXPECT_EQ(check.degenerateQuads, 0u);
  EXPECT_EQ(check.nonManifoldEdges, 0u);
  EXPECT_EQ(check.eulerCharacteristic(), 2);  // a closed block: a sphere's topology
  // The top: vertices well inside the footprint lie at 6.5 m with normals straight up (one a
  // stack; cells shared by two nodes have a copy in each).
  std::set<std::pair<float, float>> top;
  for (const StackVertex& v : mesh.vertices) {
    if (v.position[0] < 3 || v.position[0] > 16 || v.position[1] < 3 || v.position[1] > 8 ||
        v.position[2] < 4) {
      continue;
    }
    top.insert({v.position[0], v.position[1]});
    EXPECT_NEAR(v.position[2], 6.5f, 1e-4f);
    EXPECT_NEAR(v.normal[2], 1.0f, 1e-5f);
    EXPECT_NEAR(v.materials[0], 1.0f, 1e-6f);
  }
  EXPECT_EQ(top.size(), 13u * 5u);  // cell centres 3.5 .. 15.5 by 3.5 .. 7.5
}

TEST(Quadrangulation, FacesWindCounterClockwiseSeenFromOutside) {
  // A block with a cave inside (air from 3 to 6 m in the middle): cave floor faces up, its
  // ceiling down, and every quad's winding agrees with its vertices' normals.
  const QuantisedStacks stacks = stacksOf(16, 16, [](int x, int y) {
    if (x >= 5 && x < 11 && y >= 5 && y < 11) {
      return std::vector<StackLayer>{{0.0f, 3.0f, 1}, {6.0f, 10.0f, 1}};
    }
    return std::vector<StackLayer>{{0.0f, 10.0f, 1}};
  });
  QuadParams params;
  params.nodeCells = 9;
  const StackMesh mesh = wholeTerrain(stacks, params);
  const StackMeshCheck check = checkStackMesh(mesh);
  EXPECT_TRUE(check.watertight());
  EXPECT_EQ(check.eulerCharacteristic(), 4);  // two closed surfaces: the block and the cave
  std::size_t disagreeing = 0;
  for (std::size_t q = 0; q < mesh.indices.size(); q += 6) {
    const auto& a = mesh.vertices[mesh.indices[q]].position;
    const auto& b = mesh.vertices[mesh.indices[q + 1]].position;
    const auto& c = mesh.vertices[mesh.indices[q + 2]].position;
    const float ux = b[0] - a[0], uy = b[1] - a[1], uz = b[2] - a[2];
    const float vx = c[0] - a[0], vy = c[1] - a[1], vz = c[2] - a[2];
    const float nx = uy * vz - uz * vy, ny = uz * vx - ux * vz, nz = ux * vy - uy * vx;
    float dot = 0.0f;
    for (int k = 0; k < 3; ++k) {
      const auto& n = mesh.vertices[mesh.indices[q + std::size_t(k)]].normal;
      dot += n[0] * nx + n[1] * ny + n[2] * nz;
    }
    if (!(dot > 0.0f)) ++disagreeing;
  }
  EXPECT_EQ(disagreeing, 0u) << "of " << mesh.quadCount() << " quads";
}

TEST(Quadrangulation, AnArchHasATunnel) {
  // Two pillars joined by a deck: a closed surface of genus 1 (Euler characteristic 0).
  const QuantisedStacks stacks = stacksOf(24, 8, [](int x, int y) {
    std::vector<StackLayer> column{{0.0f, 2.0f, 1}};  // ground
    if (y < 2 || y >= 6) return column;
    if (x >= 4 && x < 9) column = {{0.0f, 14.0f, 1}};  // pillars
    else if (x >= 15 && x < 20) column = {{0.0f, 14.0f, 1}};
    else if (x >= 9 && x < 15) column.push_back({9.0f, 14.0f, 1});  // deck over air
    return column;
  });
  QuadParams params;
  params.nodeCells = 7;
  const StackMeshCheck check = checkStackMesh(wholeTerrain(stacks, params));
  EXPECT_TRUE(check.watertight());
  EXPECT_EQ(check.nonManifoldEdges, 0u);
  EXPECT_EQ(check.eulerCharacteristic(), 0);
}

TEST(Quadrangulation, SkippedNodesHaveNoSurfaceAndNodeSizeDoesNotChangeTheSurface) {
  Result<StackTerrain> terrain = test::hillsWithCaves(
      {.width = 48, .height = 40, .waveX = 0.2, .waveY = 0.15, .riseM = 0.8, .caveScaleM = 24.0});
  ASSERT_TRUE(terrain) << terrain.error().message;
  Result<QuantisedStacks> stacks = QuantisedStacks::from(terrain.value(), 2.0);
  ASSERT_TRUE(stacks);
  QuadParams params;
  params.nodeCells = 9;
  const NodeGrid nodes = NodeGrid::of(stacks.value(), params);
  std::vector<NodeKey> all;
  for (int z = 0; z < nodes.nodesZ; ++z) {
    for (int y = 0; y < nodes.nodesY; ++y) {
      for (int x = 0; x < nodes.nodesX; ++x) all.push_back({x, y, z});
    }
  }
  const std::vector<NodeKey> surface = nodesWithSurface(stacks.value(), params);
  EXPECT_LT(surface.size(), all.size());
  const StackMesh everything = quadrangulateNodes(stacks.value(), params, all);
  const StackMesh skipped = quadrangulateNodes(stacks.value(), params, surface);
  EXPECT_EQ(everything.quadCount(), skipped.quadCount());
  const StackMeshCheck check = checkStackMesh(skipped);
  EXPECT_TRUE(check.watertight()) << check.unbalancedEdges;
  EXPECT_EQ(check.degenerateQuads, 0u);
  // Other node sizes cut the same surface into other nodes: the same welded mesh.
  params.nodeCells = 17;
  const StackMeshCheck larger = checkStackMesh(wholeTerrain(stacks.value(), params));
  EXPECT_EQ(larger.quads, check.quads);
  EXPECT_EQ(larger.vertices, check.vertices);
  EXPECT_EQ(larger.eulerCharacteristic(), check.eulerCharacteristic());
}

}  // namespace
}  // namespace tellus
