// BDAM's exact leaves (lod/bdam/bdam_exact_leaf.hpp): every leaf drawn exact, with the cells
// along north-west edges owned by one side, is the reference's triangulation of the grid, cell
// for cell (each split south-west / north-east, once); an exact leaf beside stored patches keeps
// every sample on its edges and tiles its triangle; the leaf across an edge is found.
#include <algorithm>
#include <array>
#include <map>
#include <set>
#include <vector>

#include <gtest/gtest.h>

#include "tellus/formats/bdam/bdam_patches.hpp"
#include "tellus/lod/bdam/bdam_exact_leaf.hpp"

namespace tellus::bdam {
namespace {

HeightGrid rampGrid(int width, int height) {
  HeightGrid grid(width, height);
  grid.spacingXM = grid.spacingYM = 30.0;
  for (int r = 0; r < height; ++r) {
    for (int c = 0; c < width; ++c) grid.at(c, r) = float((c * 7 + r * 13) % 29);
  }
  return grid;
}

using Corners = std::array<glm::ivec2, 3>;

// The leaf's triangles in grid samples, each rotated to start at its smallest corner (so that
// equal triangles compare equal, winding kept).
std::vector<Corners> trianglesOf(const ExactLeafMesh& mesh) {
  std::vector<Corners> out;
  for (std::size_t i = 0; i + 2 < mesh.indices.size(); i += 3) {
    Corners t;
    for (int k = 0; k < 3; ++k) {
      const PackedVertex& v = mesh.vertices[mesh.indices[i + std::size_t(k)]];
      t[std::size_t(k)] = glm::ivec2(mesh.origin) + glm::ivec2(v.x, v.y);
    }
    const auto less = [](glm::ivec2 a, glm::ivec2 b) { return a.x != b.x ? a.x < b.x : a.y < b.y; };
    while (!(less(t[0], t[1]) && less(t[0], t[2]))) std::rotate(t.begin(), t.begin() + 1, t.end());
    out.push_back(t);
  }
  return out;
}

std::array<int, 6> key(const Corners& t) { return {t[0].x, t[0].y, t[1].x, t[1].y, t[2].x, t[2].y}; }

// The reference's triangles of cell (x, y), counter-clockwise, rotated as trianglesOf does.
std::array<Corners, 2> referenceCell(int x, int y) {
  const glm::ivec2 sw{x, y}, se{x + 1, y}, ne{x + 1, y + 1}, nw{x, y + 1};
  return {Corners{sw, se, ne}, Corners{sw, ne, nw}};
}

// The cut each leaf takes when every leaf of `level` is drawn exact: the lower node of two
// across a north-west edge owns its cells.
CutCells cutWhenAllExact(NodeId node, int level, int domainLog2) {
  const Triangle t = nodeTriangle(node, domainLog2);
  glm::ivec2 a, b;
  if (!northwestEdge(t, a, b)) return CutCells::Half;
  const NodeId across = nodeAcross(t, a, b, level, domainLog2);
  if (across == 0) return CutCells::Half;  // the domain's edge
  return node < across ? CutCells::Whole : CutCells::None;
}

// Leaves of both parities (odd levels: axis-aligned hypotenuse and 45-degree legs; even levels:
// the reverse), on grids filling the domain and cut by it.
TEST(BdamExactLeaf, AllLeavesExactAreTheReferenceTriangulation) {
  for (const auto& [width, height] : {std::pair{65, 65}, std::pair{61, 47}}) {
    const HeightGrid grid = rampGrid(width, height);
    const int domainLog2 = 6;
    for (int level : {5, 6, 7, 8}) {
      std::map<std::array<int, 6>, int> drawn;
      for (NodeId node = NodeId(2) << level; node < NodeId(4) << level; ++node) {
        const ExactLeafMesh mesh = exactLeafMesh(grid, node, domainLog2, cutWhenAllExact(node, level, domainLog2));
        for (const Corners& t : trianglesOf(mesh)) ++drawn[key(t)];
        for (const PackedVertex& v : mesh.vertices) {
          const glm::ivec2 p = glm::ivec2(mesh.origin) + glm::ivec2(v.x, v.y);
          ASSERT_EQ(v.heightM, sampleHeight(grid, p));
        }
      }
      std::map<std::array<int, 6>, int> reference;
      for (int y = 0; y + 1 < height; ++y) {
        for (int x = 0; x + 1 < width; ++x) {
          for (const Corners& t : referenceCell(x, y)) reference[key(t)] = 1;
        }
      }
      EXPECT_EQ(drawn, reference) << width << " x " << height << ", level " << level;
    }
  }
}

// Beside stored patches (every cut cell halved), an exact leaf covers its triangle exactly (its
// triangles' area is the triangle's, within the grid) and puts a vertex on every sample of its
// edges, as the stored leaves' locked legs and a mate's hypotenuse do.
TEST(BdamExactLeaf, AnExactLeafBesideStoredPatchesKeepsEverySampleOnItsEdges) {
  const HeightGrid grid = rampGrid(65, 65);
  const int domainLog2 = 6;
  for (int level : {5, 6, 7, 8}) {
    for (NodeId node = NodeId(2) << level; node < NodeId(4) << level; ++node) {
      const Triangle t = nodeTriangle(node, domainLog2);
      const ExactLeafMesh mesh = exactLeafMesh(grid, node, domainLog2, CutCells::Half);
      long long twiceArea = 0;
      for (const Corners& c : trianglesOf(mesh)) {
        const long long a = orient(c[0], c[1], c[2]);
        ASSERT_GT(a, 0) << "clockwise or flat triangle in leaf " << node;
        twiceArea += a;
      }
      EXPECT_EQ(twiceArea, std::llabs(orient(t.apex, t.left, t.right))) << "leaf " << node;
      std::set<std::pair<int, int>> vertices;
      for (const PackedVertex& v : mesh.vertices) vertices.emplace(int(mesh.origin.x) + v.x, int(mesh.origin.y) + v.y);
      for (const auto& [a, b] : {std::pair{t.apex, t.left}, std::pair{t.left, t.right}, std::pair{t.right, t.apex}}) {
        const glm::ivec2 d = b - a;
        const int steps = std::max(std::abs(d.x), std::abs(d.y));
        for (int k = 0; k <= steps; ++k) {
          const glm::ivec2 p = a + d / steps * k;
          EXPECT_TRUE(vertices.contains({p.x, p.y})) << "leaf " << node << " misses sample " << p.x << "," << p.y;
        }
      }
    }
  }
}

// The leaf across a north-west edge shares that edge, and the leaf across it again is the first.
TEST(BdamExactLeaf, TheLeafAcrossANorthwestEdgeSharesIt) {
  const int domainLog2 = 6;
  int found = 0;
  for (int level : {5, 6, 7, 8}) {
    for (NodeId node = NodeId(2) << level; node < NodeId(4) << level; ++node) {
      const Triangle t = nodeTriangle(node, domainLog2);
      glm::ivec2 a, b;
      if (!northwestEdge(t, a, b)) continue;
      const NodeId across = nodeAcross(t, a, b, level, domainLog2);
      if (across == 0) continue;  // on the domain's border
      ++found;
      const Triangle u = nodeTriangle(across, domainLog2);
      glm::ivec2 c, d;
      ASSERT_TRUE(northwestEdge(u, c, d)) << node << " / " << across;
      EXPECT_TRUE((c == a && d == b) || (c == b && d == a)) << node << " / " << across;
      EXPECT_EQ(nodeAcross(u, c, d, level, domainLog2), node);
    }
  }
  EXPECT_GT(found, 100);
}

}  // namespace
}  // namespace tellus::bdam
