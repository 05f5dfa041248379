// BDAM's GL-free parts (seed 004 section 2.2): the triangle bintree, the patches simplified with
// locked borders (every shared edge has one vertex set, whatever the two patches' levels), the
// patch file round trip and its corruption errors, and the run-time selection (nested diamond
// errors and boxes, a conforming cut that meets the error target).
#include <algorithm>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>

#include <gtest/gtest.h>

#include "support/test_support.hpp"
#include "tellus/bdam/bdam_file.hpp"
#include "tellus/bdam/bdam_patches.hpp"
#include "tellus/dem/terrain_generator.hpp"
#include "tellus/lod/bdam/bdam_selection.hpp"

namespace tellus::bdam {
namespace {

HeightGrid terrain(int width, int height, std::uint64_t seed = 5) {
  TerrainParams params;
  params.size = std::max(width, height);
  params.seed = seed;
  params.spacingM = 30.0;
  params.erosion = 0.0;
  HeightGrid square = generateTerrain(params);
  HeightGrid grid(width, height);
  grid.spacingXM = grid.spacingYM = 30.0;
  for (int r = 0; r < height; ++r) {
    for (int c = 0; c < width; ++c) grid.at(c, r) = square.at(c, r);
  }
  return grid;
}

// The patch's vertices on segment [a, b], sorted.
std::vector<std::pair<int, int>> onEdge(const Patch& p, glm::ivec2 a, glm::ivec2 b) {
  std::vector<std::pair<int, int>> out;
  for (const glm::ivec2& q : p.positions) {
    if (onSegment(q, a, b)) out.emplace_back(q.x, q.y);
  }
  std::sort(out.begin(), out.end());
  return out;
}

class BdamPatches : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    grid_ = new HeightGrid(terrain(301, 257));  // not a power of two: patches cut by the grid's edges
    BuildSettings settings;
    settings.leafLog2 = 9;
    settings.patchTriangles = 128;
    Result<Hierarchy> built = buildHierarchy(*grid_, settings);
    ASSERT_TRUE(built) << built.error().message;
    hierarchy_ = new Hierarchy(std::move(built.value()));
  }
  static void TearDownTestSuite() {
    delete grid_;
    delete hierarchy_;
  }
  static const Patch* find(NodeId node) {
    const auto it = std::lower_bound(hierarchy_->patches.begin(), hierarchy_->patches.end(), node,
                                     [](const Patch& p, NodeId n) { return p.node < n; });
    return it != hierarchy_->patches.end() && it->node == node ? &*it : nullptr;
  }
  static HeightGrid* grid_;
  static Hierarchy* hierarchy_;
};
HeightGrid* BdamPatches::grid_ = nullptr;
Hierarchy* BdamPatches::hierarchy_ = nullptr;

TEST(BdamBintree, ChildrenSplitTheHypotenuseAndTileTheParent) {
  for (NodeId node = 2; node < 64; ++node) {
    const Triangle t = nodeTriangle(node, 4);
    const Triangle a = nodeTriangle(2 * node, 4), b = nodeTriangle(2 * node + 1, 4);
    EXPECT_EQ(a.apex, t.hypotenuseMidpoint());
    EXPECT_EQ(b.apex, t.hypotenuseMidpoint());
    EXPECT_EQ(std::llabs(orient(a.apex, a.left, a.right)) + std::llabs(orient(b.apex, b.left, b.right)),
              std::llabs(orient(t.apex, t.left, t.right)));
    EXPECT_EQ(nodeLevel(2 * node), nodeLevel(node) + 1);
  }
}

TEST_F(BdamPatches, EveryLevelIsSimplifiedTowardsItsTarget) {
  ASSERT_GT(hierarchy_->leafLevel, 4);
  std::map<int, std::pair<std::size_t, std::size_t>> perLevel;  // level -> (patches, triangles)
  for (const Patch& p : hierarchy_->patches) {
    auto& [patches, triangles] = perLevel[nodeLevel(p.node)];
    ++patches;
    triangles += p.indices.size() / 3;
  }
  // A leaf covers 512 half-cells: simplified to 128 triangles (a few more where borders are locked).
  const auto& [leaves, leafTriangles] = perLevel[hierarchy_->leafLevel];
  EXPECT_LT(double(leafTriangles) / double(leaves), 200.0);
  // The root patches hold a whole-terrain approximation in about 2 x 128 triangles.
  EXPECT_LT(perLevel[0].second, 600u);
}

TEST_F(BdamPatches, SharedEdgesHaveOneVertexSetAcrossLevels) {
  std::size_t compared = 0;
  for (const Patch& p : hierarchy_->patches) {
    const Triangle t = nodeTriangle(p.node, hierarchy_->domainLog2);
    // The mate across the hypotenuse (same level) puts the same vertices on it.
    const glm::ivec2 m = t.hypotenuseMidpoint();
    for (const Patch& q : hierarchy_->patches) {
      if (&q == &p || nodeLevel(q.node) != nodeLevel(p.node)) continue;
      const Triangle u = nodeTriangle(q.node, hierarchy_->domainLog2);
      if (u.hypotenuseMidpoint() != m) continue;
      EXPECT_EQ(onEdge(p, t.left, t.right), onEdge(q, u.left, u.right)) << "mates " << p.node << " " << q.node;
      ++compared;
    }
    // Each leg is a child's hypotenuse: the finer patch puts the same vertices on it.
    for (int which = 0; which < 2; ++which) {
      const Patch* child = find(2 * p.node + NodeId(which));
      if (!child) continue;
      const Triangle c = nodeTriangle(child->node, hierarchy_->domainLog2);
      EXPECT_EQ(onEdge(p, c.left, c.right), onEdge(*child, c.left, c.right)) << "leg of " << p.node;
      ++compared;
    }
  }
  EXPECT_GT(compared, hierarchy_->patches.size());
}

}  // namespace
}  // namespace tellus::bdam
