// The octree LOD of stack terrain (lod/stacks/): the seed's screen-space extent, a balanced
// selection, and the stitched quadrangulation's CPU reference: a mixed-level selection whose
// node meshes together form one closed surface (every border vertex shared, no crack).
#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <set>

#include "support/stack_fixtures.hpp"
#include "tellus/lod/stacks/stack_level_error.hpp"
#include "tellus/lod/stacks/stack_levels.hpp"
#include "tellus/lod/stacks/seam_blend.hpp"
#include "tellus/lod/stacks/stack_octree.hpp"
#include "tellus/lod/stacks/stitched_quadrangulation.hpp"
#include "tellus/formats/stacks/dual_contouring.hpp"
#include "tellus/formats/stacks/stack_aggregation.hpp"
#include "tellus/formats/stacks/stack_edit.hpp"
#include "tellus/formats/stacks/stack_generator.hpp"
#include "tellus/formats/stacks/stack_mesh_check.hpp"

namespace tellus {
namespace {

// A hilly terrain of 96 x 80 stacks 4 m apart with caves, and its pyramid.
std::vector<StackTerrain> testPyramid() {
  Result<StackTerrain> terrain = test::hillsWithCaves({});
  EXPECT_TRUE(terrain) << terrain.error().message;
  return buildStackPyramid(std::move(terrain.value()));
}

StackLevels testLevels(int nodeCells = 9) {
  QuadParams params;
  params.nodeCells = nodeCells;
  Result<StackLevels> levels = StackLevels::build(testPyramid(), 2.0, params);
  EXPECT_TRUE(levels) << levels.error().message;
  return std::move(levels.value());
}

SelectionView lowCamera() {
  SelectionView view;
  view.camera = {40.0, 60.0, 90.0};
  view.fovYDeg = 60.0;
  view.viewportHeightPx = 720;
  view.tauPx = 60.0;  // a small terrain: coarse levels within a few hundred metres
  return view;
}

// Node cell ranges in level-0 cells, for sharing tests.
std::array<std::array<int, 2>, 3> cellRange(const StackOctree& octree, const OctreeKey& key) {
  const std::array<int, 3> o = octree.origin(key);
  const int scale = 1 << key.level;
  std::array<std::array<int, 2>, 3> r{};
  for (int a = 0; a < 3; ++a) r[std::size_t(a)] = {o[std::size_t(a)] * scale, (o[std::size_t(a)] + octree.nodeCells()) * scale};
  return r;
}

TEST(StackOctree, ExtentIsTheSeedsFormula) {
  SelectionView view;
  view.fovYDeg = 90.0;
  view.viewportHeightPx = 1000;
  // eps = delta w / (2 d tan(phi / 2)) = 2 * 1000 / (2 * 10 * 1).
  EXPECT_NEAR(view.extentPx(2.0, 10.0), 100.0, 1e-9);
  EXPECT_NEAR(view.extentPx(2.0, 20.0), 50.0, 1e-9);
  EXPECT_TRUE(std::isinf(view.extentPx(2.0, 0.0)));
}

TEST(StackOctree, LevelsNestAndRejectBadNodeSizes) {
  const StackLevels levels = testLevels();
  ASSERT_GE(levels.count(), 4);
  for (int k = 0; k < levels.count(); ++k) {
    const QuantisedStacks& s = levels.level(k).stacks;
    EXPECT_DOUBLE_EQ(s.spacingM, 4.0 * std::ldexp(1.0, k));
    EXPECT_DOUBLE_EQ(s.cellM, 2.0 * std::ldexp(1.0, k));
    // Sample z of level k lies on sample 2^k z of level 0.
    EXPECT_DOUBLE_EQ(s.baseM + 0.5 * s.cellM, 0.5 * 2.0);
  }
  QuadParams even;
  even.nodeCells = 16;
  EXPECT_FALSE(StackLevels::build(testPyramid(), 2.0, even));
  QuadParams small;
  small.nodeCells = 7;
  EXPECT_FALSE(StackLevels::build(testPyramid(), 2.0, small));
}

// Edits touch only their regions (stacks, MipMap, quantised levels, height ranges, errors),
// and the result equals quantising the edited pyramid anew, at every level.
TEST(StackOctree, AnEditedLevelSetEqualsAFreshBuild) {
  std::vector<StackTerrain> pyramid = testPyramid();
  QuadParams params;
  params.nodeCells = 9;
  Result<StackLevels> edited = StackLevels::build(pyramid, 2.0, params);
  ASSERT_TRUE(edited) << edited.error().message;
  const std::vector<SphereEdit> strokes{{100.0, 120.0, 40.0, 14.0, kAir},
                                        {250.0, 200.0, 70.0, 9.0, kStackRock},
                                        {2.0, 300.0, 20.0, 11.0, kStackSoil},  // at the border
                                        {380.0, 10.0, 160.0, 8.0, kStackRock}};  // above the top
  for (const SphereEdit& stroke : strokes) {
    Result<StackRegion> region = applySphereEdit(pyramid.front(), stroke);
    ASSERT_TRUE(region) << region.error().message;
    ASSERT_FALSE(region->empty());
    ASSERT_TRUE(edited->rebuild(pyramid, updatePyramid(pyramid, region.value())));
  }
  Result<StackLevels> fresh = StackLevels::build(buildStackPyramid(pyramid.front()), 2.0, params);
  ASSERT_TRUE(fresh);
  ASSERT_EQ(edited->count(), fresh->count());
  EXPECT_EQ(edited->topM(), fresh->topM());
  for (int k = 0; k < fresh->count(); ++k) {
    const StackLevel& a = edited->level(k);
    const StackLevel& b = fresh->level(k);
    EXPECT_EQ(a.stacks.offsets, b.stacks.offsets) << "level " << k;
    ASSERT_EQ(a.stacks.layers.size(), b.stacks.layers.size()) << "level " << k;
    for (std::size_t i = 0; i < a.stacks.layers.size(); ++i) {
      const QuantisedLayer &p = a.stacks.layers[i], &q = b.stacks.layers[i];
      ASSERT_TRUE(p.bottom == q.bottom && p.top == q.top && p.channel == q.channel)
          << "level " << k << " layer " << i;
    }
    EXPECT_EQ(a.stacks.cellsZ, b.stacks.cellsZ) << "level " << k;
    EXPECT_EQ(a.lowestBoundaryM, b.lowestBoundaryM) << "level " << k;
    EXPECT_EQ(a.highestTopM, b.highestTopM) << "level " << k;
    EXPECT_EQ(a.errorM, b.errorM) << "level " << k;
  }
  // A region outside the grid is refused and changes nothing.
  QuantisedStacks copy = edited->level(0).stacks;
  EXPECT_FALSE(copy.replaceRegion(pyramid.front(), {0, 0, copy.width, 3}));
  EXPECT_EQ(copy.offsets, edited->level(0).stacks.offsets);
}

TEST(StackLevelError, ALostRoofIsAnErrorAsLargeAsTheCaveBelowIt) {
  // Fine: ground to 10 m, a cave, a roof from 20 to 22 m. Coarse: the roof lost.
  const std::vector<StackLayer> fine = {{0.0f, 10.0f, 1}, {20.0f, 22.0f, 1}};
  const std::vector<StackLayer> coarse = {{0.0f, 10.5f, 1}};
  const ColumnError lost = columnSurfaceError(coarse, fine, 1.0f);
  EXPECT_FLOAT_EQ(lost.errorM, 11.5f);  // the roof's top against the ground's top
  ASSERT_TRUE(lost.hasRange());
  EXPECT_FLOAT_EQ(lost.lowM, 10.5f);
  EXPECT_FLOAT_EQ(lost.highM, 22.0f);
  // A surface moved by less than the tolerance: an error, but nowhere to refine for.
  const ColumnError moved = columnSurfaceError(coarse, {{{0.0f, 10.0f, 1}}}, 1.0f);
  EXPECT_FLOAT_EQ(moved.errorM, 0.5f);
  EXPECT_FALSE(moved.hasRange());
  // Layers of two materials that touch are one solid run (no surface between them).
  const std::vector<StackLayer> twoMaterials = {{0.0f, 4.0f, 1}, {4.0f, 10.5f, 2}};
  EXPECT_FLOAT_EQ(columnSurfaceError(coarse, twoMaterials, 0.1f).errorM, 0.0f);
  // An empty column has the base as its only surface.
  EXPECT_FLOAT_EQ(columnSurfaceError({}, coarse, 0.1f).errorM, 10.5f);
}

TEST(StackLevelError, TheSmoothingKeepsRunsOfAboutACell) {
  QuadParams gauss1;  // the default: Gauss 1 2 1
  const double g1 = survivingRunCells(gauss1);
  EXPECT_NEAR(g1, 1.33, 0.02);
  QuadParams none;
  none.filterRadius = 0;
  // Without smoothing a run survives when a cell is more than half covered whatever the
  // alignment: just over one cell (a run of one cell across two halves does not).
  EXPECT_NEAR(survivingRunCells(none), 1.0, 0.05);
  EXPECT_GT(survivingRunCells(none), 1.0);
  // Wider and flatter filters need thicker runs.
  QuadParams gauss2 = gauss1, box2 = gauss1;
  gauss2.filterRadius = 2;
  box2.filterRadius = 2;
  box2.filter = SmoothingFilter::Box;
  EXPECT_GT(survivingRunCells(gauss2), g1);
  EXPECT_GT(survivingRunCells(box2), survivingRunCells(gauss2));
  EXPECT_NEAR(survivingRunCells(box2), 2.5, 0.6);  // 5 equal taps: half of them covered
}

TEST(StackLevelError, ARunTheSmoothingLosesIsAHoleAtAnyDistance) {
  // A thin terrain: one slab from 0 to 100 m. Cells of 120 m lose it, cells of 60 m keep it.
  const std::vector<StackLayer> slab = {{0.0f, 100.0f, 1}};
  const ColumnError lost = columnSurfaceError(slab, slab, 10.0f, 120.0f, 60.0f);
  EXPECT_EQ(lost.errorM, kVanishedErrorM);
  ASSERT_TRUE(lost.hasRange());
  EXPECT_FLOAT_EQ(lost.lowM, 0.0f);
  EXPECT_FLOAT_EQ(lost.highM, 100.0f);
  // Both levels keep it: no error; both lose it: nothing the finer level shows is lost here.
  EXPECT_FLOAT_EQ(columnSurfaceError(slab, slab, 10.0f, 60.0f, 30.0f).errorM, 0.0f);
  EXPECT_FLOAT_EQ(columnSurfaceError(slab, slab, 10.0f, 240.0f, 120.0f).errorM, 0.0f);
  // A coarse column with no layer at all is the old case: a finite error (aggregated away).
  EXPECT_FLOAT_EQ(columnSurfaceError({}, slab, 10.0f, 120.0f, 60.0f).errorM, 100.0f);
  // A gap thinner than a level's run is filled: a cave of 5 m under a roof of 20 m is one run
  // from 0 to 75 m at cells of 10 m, and the cave's floor (50 m) is 25 m from its surfaces.
  const std::vector<StackLayer> cave = {{0.0f, 50.0f, 1}, {55.0f, 75.0f, 1}};
  const ColumnError filled = columnSurfaceError(cave, cave, 1.0f, 10.0f, 0.0f);
  EXPECT_FLOAT_EQ(filled.errorM, 25.0f);
  EXPECT_FLOAT_EQ(filled.lowM, 50.0f);
  EXPECT_FLOAT_EQ(filled.highM, 75.0f);
}

TEST(StackOctree, TheGeometricErrorRefinesWhereCoarseLevelsLoseCaves) {
  const StackLevels levels = testLevels();
  // The caves make errors of several metres at coarse levels, 0 at level 0.
  EXPECT_TRUE(levels.level(0).errorM.empty());
  float worst = 0.0f;
  for (float e : levels.level(2).errorM) worst = std::max(worst, e);
  EXPECT_GT(worst, 4.0f);
  const StackOctree octree(levels);
  SelectionView seedOnly = lowCamera();
  SelectionView withError = seedOnly;
  withError.errorTauPx = seedOnly.tauPx;
  const StackSelection a = selectStackNodes(octree, seedOnly);
  const StackSelection b = selectStackNodes(octree, withError);
  EXPECT_GT(b.nodes.size(), a.nodes.size());
  for (const SelectedNode& node : b.nodes) {
    if (node.key.level > 0) {
      EXPECT_LE(node.errorPx, withError.errorTauPx);
    }
  }
  for (const SelectedNode& node : a.nodes) EXPECT_EQ(node.errorPx, 0.0);  // not computed
}

TEST(StackOctree, SelectionRefinesNearTheCameraAndIsBalanced) {
  const StackLevels levels = testLevels();
  const StackOctree octree(levels);
  const SelectionView view = lowCamera();
  const StackSelection selection = selectStackNodes(octree, view);
  ASSERT_FALSE(selection.nodes.empty());
  EXPECT_EQ(selection.finestLevel, 0);
  EXPECT_GE(selection.coarsestLevel, 2);
  // Every leaf meets the criterion or is at level 0; its parent did not.
  for (const SelectedNode& node : selection.nodes) {
    if (node.key.level > 0) {
      EXPECT_LE(node.extentPx, view.tauPx);
    }
  }
  // Nodes that share a cell are at most one level apart, and never overlap by more than the
  // one-cell border (no node lies inside another).
  std::size_t pairs = 0;
  for (std::size_t a = 0; a < selection.nodes.size(); ++a) {
    for (std::size_t b = a + 1; b < selection.nodes.size(); ++b) {
      const auto ra = cellRange(octree, selection.nodes[a].key);
      const auto rb = cellRange(octree, selection.nodes[b].key);
      bool share = true;
      for (int i = 0; i < 3; ++i) {
        share = share && ra[std::size_t(i)][0] < rb[std::size_t(i)][1] && rb[std::size_t(i)][0] < ra[std::size_t(i)][1];
      }
      if (!share) continue;
      ++pairs;
      EXPECT_LE(std::abs(selection.nodes[a].key.level - selection.nodes[b].key.level), 1);
    }
  }
  EXPECT_GT(pairs, selection.nodes.size());
  // Deterministic.
  const StackSelection again = selectStackNodes(octree, view);
  ASSERT_EQ(again.nodes.size(), selection.nodes.size());
  for (std::size_t i = 0; i < again.nodes.size(); ++i) {
    EXPECT_EQ(again.nodes[i].key, selection.nodes[i].key);
    EXPECT_EQ(again.nodes[i].stitchMask, selection.nodes[i].stitchMask);
  }
}

TEST(StackOctree, UnstitchedNodeIsThePlainPipelineAtItsLevel) {
  const StackLevels levels = testLevels();
  const StackOctree octree(levels);
  // The level-1 node with the most quads.
  OctreeKey key{1, 0, 0, 0};
  StackMesh plain;
  const std::array<int, 3> end = octree.nodesEnd(1);
  for (int z = -1; z < end[2]; ++z) {
    for (int y = -1; y < end[1]; ++y) {
      for (int x = -1; x < end[0]; ++x) {
        StackMesh mesh;
        quadrangulateNode(levels.level(1).stacks, levels.params(), octree.origin({1, x, y, z}), mesh);
        if (mesh.quadCount() > plain.quadCount()) {
          plain = std::move(mesh);
          key = {1, x, y, z};
        }
      }
    }
  }
  ASSERT_GT(plain.quadCount(), 100u);
  StackMesh stitched;
  quadrangulateStitchedNode(octree, key, 0u, stitched);
  EXPECT_EQ(stitched.indices, plain.indices);
  ASSERT_EQ(stitched.vertices.size(), plain.vertices.size());
  for (std::size_t v = 0; v < plain.vertices.size(); ++v) {
    EXPECT_EQ(stitched.vertices[v].position, plain.vertices[v].position);
  }
}

// All selected nodes, stitched, welded into one mesh.
StackMesh selectionMesh(const StackOctree& octree, const StackSelection& selection,
                        StitchStats& total) {
  StackMesh mesh;
  for (const SelectedNode& node : selection.nodes) {
    StitchStats stats;
    quadrangulateStitchedNode(octree, node.key, node.stitchMask, mesh, nullptr, &stats);
    total.coarseSamples += stats.coarseSamples;
    total.sharedVertices += stats.sharedVertices;
    total.faults += stats.faults;
  }
  return mesh;
}

TEST(StackOctree, StitchedSelectionIsOneClosedSurface) {
  for (int nodeCells : {9, 17}) {
    const StackLevels levels = testLevels(nodeCells);
    const StackOctree octree(levels);
    const StackSelection selection = selectStackNodes(octree, lowCamera());
    std::set<int> levelsSeen;
    std::size_t stitchedNodes = 0;
    for (const SelectedNode& node : selection.nodes) {
      levelsSeen.insert(node.key.level);
      if (node.stitchMask != 0u) ++stitchedNodes;
    }
    EXPECT_GE(levelsSeen.size(), 3u) << nodeCells;
    EXPECT_GT(stitchedNodes, 0u);
    StitchStats stats;
    const StackMesh mesh = selectionMesh(octree, selection, stats);
    EXPECT_EQ(stats.faults, 0u) << nodeCells;
    EXPECT_GT(stats.sharedVertices, 0u);
    const StackMeshCheck check = checkStackMesh(mesh);
    EXPECT_GT(check.quads, 1000u);
    // Closed and consistently oriented: every border edge of a node is an edge of its
    // neighbour (same level or coarser), so no crack.
    EXPECT_EQ(check.unbalancedEdges, 0u) << nodeCells;
    // Without stitching the same selection has cracks: the test can fail.
    StackMesh unstitched;
    for (const SelectedNode& node : selection.nodes) {
      quadrangulateStitchedNode(octree, node.key, 0u, unstitched);
    }
    EXPECT_GT(checkStackMesh(unstitched).unbalancedEdges, 0u) << nodeCells;
  }
}


// Geomorph targets (stitched_quadrangulation.hpp): a vertex that moves moves onto a vertex of the
// coarser level's mesh (its parent's or a neighbour's of the parent), and a vertex two
// neighbouring nodes share has one target in both (so they slide together).
TEST(StackOctree, MorphTargetsLieOnTheCoarserMeshAndAgreeAcrossNeighbours) {
  const StackLevels levels = testLevels(9);
  const StackOctree octree(levels);
  const int n = octree.nodeCells();
  const StackSelection selection = selectStackNodes(octree, lowCamera());
  std::map<std::uint64_t, const SelectedNode*> byKey;
  for (const SelectedNode& node : selection.nodes) byKey[node.key.packed()] = &node;
  const auto cellAt = [n](int i, int j, int k) { return std::size_t(i + n * (j + n * k)); };
  std::size_t checkedNodes = 0, moved = 0, sharedCompared = 0;
  for (const SelectedNode& node : selection.nodes) {
    if (node.stitchMask != 0u || node.key.level + 1 >= levels.count() || checkedNodes >= 40) continue;
    ++checkedNodes;
    StackMesh mesh;
    std::vector<CellEntry> cells;
    std::vector<MorphTarget> targets;
    quadrangulateStitchedNode(octree, node.key, 0u, mesh, &cells, nullptr, &targets);
    ASSERT_EQ(targets.size(), mesh.vertices.size());
    // Every vertex of the parent and its neighbours (the coarser meshes around).
    std::set<std::array<float, 3>> coarse;
    const OctreeKey parent = node.key.parent();
    for (int dz = -1; dz <= 1; ++dz) {
      for (int dy = -1; dy <= 1; ++dy) {
        for (int dx = -1; dx <= 1; ++dx) {
          StackMesh around;
          quadrangulateStitchedNode(octree, {parent.level, parent.x + dx, parent.y + dy, parent.z + dz},
                                    0u, around);
          for (const StackVertex& v : around.vertices) coarse.insert({v.position[0], v.position[1], v.position[2]});
        }
      }
    }
    for (std::size_t v = 0; v < mesh.vertices.size(); ++v) {
      const std::array<float, 3> own{mesh.vertices[v].position[0], mesh.vertices[v].position[1],
                                     mesh.vertices[v].position[2]};
      const std::array<float, 3> target{targets[v][0], targets[v][1], targets[v][2]};
      if (target == own) continue;
      ++moved;
      EXPECT_TRUE(coarse.contains(target)) << "vertex " << v << " of level " << node.key.level;
    }
    // The +x neighbour of the same level, unstitched too: cell n - 1 here is its cell 0.
    const auto right = byKey.find(OctreeKey{node.key.level, node.key.x + 1, node.key.y, node.key.z}.packed());
    if (right == byKey.end() || right->second->stitchMask != 0u) continue;
    StackMesh other;
    std::vector<CellEntry> otherCells;
    std::vector<MorphTarget> otherTargets;
    quadrangulateStitchedNode(octree, right->second->key, 0u, other, &otherCells, nullptr, &otherTargets);
    for (int k = 0; k < n; ++k) {
      for (int j = 0; j < n; ++j) {
        const CellEntry& a = cells[cellAt(n - 1, j, k)];
        const CellEntry& b = otherCells[cellAt(0, j, k)];
        ASSERT_EQ(dc::codeHasVertex(a.code), dc::codeHasVertex(b.code));
        if (!dc::codeHasVertex(a.code)) continue;
        EXPECT_EQ(mesh.vertices[a.vertexIndex].position, other.vertices[b.vertexIndex].position);
        for (std::size_t c = 0; c < 3; ++c) {
          EXPECT_EQ(targets[a.vertexIndex][c], otherTargets[b.vertexIndex][c]);
        }
        // Border bits: last along x here, first along x there.
        EXPECT_TRUE(unsigned(targets[a.vertexIndex][3]) & 2u);
        EXPECT_TRUE(unsigned(otherTargets[b.vertexIndex][3]) & 1u);
        ++sharedCompared;
      }
    }
  }
  EXPECT_GE(checkedNodes, 10u);
  EXPECT_GT(moved, 500u);
  EXPECT_GT(sharedCompared, 20u);
}

// Seam blend (seam_blend.hpp): a node takes the coarser surface next to a coarser neighbour, by a
// weight 1 one cell from it falling to 0 past the band.
TEST(SeamBlend, WeightIsOneNextToACoarserNodeAndZeroPastTheBand) {
  const int n = 17;
  // The upper x half of its parent (key x odd), the parent's +x neighbour coarser: that node
  // starts at cell 16 here.
  const std::uint32_t seam = seamBits(1u << neighbourBit(1, 0, 0), 3, 2, 2);
  const auto weightAt = [&](int x, int band) { return seamBlendWeight({x, 8, 8}, seam, n, band); };
  EXPECT_EQ(weightAt(16, 4), 1.0f);  // the stitched border cell
  EXPECT_EQ(weightAt(15, 4), 1.0f);
  EXPECT_EQ(weightAt(14, 4), 0.75f);
  EXPECT_EQ(weightAt(13, 4), 0.5f);
  EXPECT_EQ(weightAt(12, 4), 0.25f);
  EXPECT_EQ(weightAt(11, 4), 0.0f);
  EXPECT_EQ(weightAt(0, 4), 0.0f);
  EXPECT_EQ(weightAt(14, 0), 0.0f);  // off
  // The band is limited to (n - 1) / 2 - 1 = 7 cells: 0 from 8 cells away.
  EXPECT_EQ(seamBandLimit(n), 7);
  EXPECT_EQ(weightAt(16 - 8, 20), 0.0f);
  EXPECT_GT(weightAt(16 - 7, 20), 0.0f);
  // The lower x half (key x even): the same neighbour is a whole node further, out of reach.
  EXPECT_EQ(seamBlendWeight({16, 8, 8}, seamBits(1u << neighbourBit(1, 0, 0), 2, 2, 2), n, 7), 0.0f);
  // A diagonal neighbour: the Chebyshev distance to its corner.
  const std::uint32_t corner = seamBits(1u << neighbourBit(1, 1, 0), 3, 3, 2);
  EXPECT_EQ(seamBlendWeight({14, 16, 8}, corner, n, 4), 0.75f);
  EXPECT_EQ(seamBlendWeight({14, 13, 8}, corner, n, 4), 0.5f);
  // The cell round-trips through MorphTarget's w, border bits kept.
  const MorphTarget target{0.0f, 0.0f, 0.0f, packMorphTargetCell({16, 0, 5}, n)};
  EXPECT_EQ(morphTargetCell(target), (std::array<int, 3>{16, 0, 5}));
  EXPECT_EQ(morphTargetBorderBits(target), (1u << 1) | (1u << 2));
}

// Every node of a mixed-level selection with the seam blend baked in at the largest band, drawn
// as the vertex shader draws it with the finest level's nodes sliding halfway, still forms one
// closed surface: every node sharing a vertex moves it alike. Weights that ignore where the node
// lies in its parent (the child bits) break it: the test can fail.
TEST(SeamBlend, NodesSharingAVertexDrawItAtOnePlace) {
  for (int nodeCells : {9, 17}) {
    const StackLevels levels = testLevels(nodeCells);
    const StackOctree octree(levels);
    const int band = seamBandLimit(nodeCells);
    const StackSelection selection = selectStackNodes(octree, lowCamera());
    std::map<std::uint64_t, std::size_t> index;
    for (std::size_t i = 0; i < selection.nodes.size(); ++i) index[selection.nodes[i].key.packed()] = i;
    const int finest = selection.finestLevel;
    // The finest level's nodes slide (factor 0.5), alike among themselves; the rest do not.
    const auto slides = [&](const OctreeKey& key) { return key.level == finest; };
    std::size_t blended = 0;
    StackMesh drawn, wrong;
    for (const SelectedNode& node : selection.nodes) {
      StackMesh plain, baked;
      std::vector<MorphTarget> targets;
      quadrangulateStitchedNode(octree, node.key, node.stitchMask, plain, nullptr, nullptr, &targets);
      quadrangulateStitchedNode(octree, node.key, node.stitchMask, baked, nullptr, nullptr, nullptr, band);
      ASSERT_EQ(plain.vertices.size(), baked.vertices.size());
      std::uint32_t unlike = 0;
      for (int dz = -1; dz <= 1; ++dz) {
        for (int dy = -1; dy <= 1; ++dy) {
          for (int dx = -1; dx <= 1; ++dx) {
            const OctreeKey other{node.key.level, node.key.x + dx, node.key.y + dy, node.key.z + dz};
            if (!index.contains(other.packed()) || slides(other) != slides(node.key)) {
              unlike |= 1u << neighbourBit(dx, dy, dz);
            }
          }
        }
      }
      const float factor = slides(node.key) ? 0.5f : 1.0f;
      const std::uint32_t wrongSeam = seamBits(node.stitchMask, 0, 0, 0);
      const auto first = std::uint32_t(drawn.vertices.size());
      for (std::size_t v = 0; v < baked.vertices.size(); ++v) {
        if (baked.vertices[v].position != plain.vertices[v].position) ++blended;
        StackVertex vertex = baked.vertices[v];
        const std::array<float, 3> at = drawnStackVertexPosition(
            {vertex.position[0], vertex.position[1], vertex.position[2]}, targets[v], factor, unlike);
        for (std::size_t a = 0; a < 3; ++a) vertex.position[a] = at[a];
        drawn.vertices.push_back(vertex);
        // The same blend with the child bits left out (every node taken as its parent's first).
        StackVertex bad = plain.vertices[v];
        const float w = seamBlendWeight(morphTargetCell(targets[v]), wrongSeam, nodeCells, band);
        for (std::size_t a = 0; a < 3; ++a) bad.position[a] = targets[v][a] * w + bad.position[a] * (1.0f - w);
        wrong.vertices.push_back(bad);
      }
      for (std::uint32_t i : baked.indices) {
        drawn.indices.push_back(first + i);
        wrong.indices.push_back(first + i);
      }
    }
    const StackMeshCheck check = checkStackMesh(drawn);
    EXPECT_GT(check.quads, 1000u);
    EXPECT_GT(blended, 200u) << nodeCells;
    EXPECT_EQ(check.unbalancedEdges, 0u) << nodeCells;
    EXPECT_GT(checkStackMesh(wrong).unbalancedEdges, 0u) << nodeCells;
  }
}

}  // namespace
}  // namespace tellus
