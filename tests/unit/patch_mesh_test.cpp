// The static patch meshes and the stitching rule (the vertex shader's CPU twin): for every
// orientation and edge of the seed's look-up, a stitched edge has exactly the coarser
// neighbour's vertices and segments (no crack, no T-junction), and unstitched edges keep theirs.
#include <bit>
#include <set>

#include <gtest/gtest.h>

#include "tellus/lod/rings/patch_mesh.hpp"
#include "tellus/lod/rings/rings_structure.hpp"

namespace tellus {
namespace {

constexpr std::array<std::uint8_t, 4> kEdges = {kEdgeUp, kEdgeRight, kEdgeDown, kEdgeLeft};

// Position of a grid point along `edge` (x on up/down edges, z on left/right), or -1 when the
// point is not on it.
int alongEdge(glm::ivec2 p, std::uint8_t edge, int cells) {
  switch (edge) {
    case kEdgeUp:
      return p.y == 0 ? p.x : -1;
    case kEdgeDown:
      return p.y == cells ? p.x : -1;
    case kEdgeLeft:
      return p.x == 0 ? p.y : -1;
    default:
      return p.x == cells ? p.y : -1;
  }
}

// The non-degenerate triangle sides lying on `edge` after stitching, as (from, to) positions.
std::set<std::pair<int, int>> edgeSegments(const PatchMesh& mesh, std::uint8_t stitch,
                                           std::uint8_t edge) {
  std::set<std::pair<int, int>> segments;
  for (std::size_t t = 0; t < mesh.indices.size(); t += 3) {
    std::array<glm::ivec2, 3> p{};
    for (int k = 0; k < 3; ++k) {
      p[std::size_t(k)] = stitchedPosition(mesh.vertices[mesh.indices[t + std::size_t(k)]], stitch);
    }
    for (int k = 0; k < 3; ++k) {
      const int a = alongEdge(p[std::size_t(k)], edge, mesh.cells);
      const int b = alongEdge(p[std::size_t((k + 1) % 3)], edge, mesh.cells);
      if (a >= 0 && b >= 0 && a != b) segments.insert({std::min(a, b), std::max(a, b)});
    }
  }
  return segments;
}

TEST(PatchMesh, VerticesCarryTheSeedsFlags) {
  Result<PatchMesh> mesh = buildPatchMesh(8);
  ASSERT_TRUE(mesh);
  EXPECT_EQ(mesh->vertices.size(), 81u);
  EXPECT_EQ(mesh->triangleCount(), 128u);
  int interior = 0, corners = 0, odd = 0, edgeVertices = 0;
  for (const PatchVertex& v : mesh->vertices) {
    const int bits = std::popcount(unsigned(v.edges));
    interior += bits == 0;
    corners += bits == 2;
    edgeVertices += bits == 1;
    odd += v.odd;
    if (bits == 0 || bits == 2) {
      EXPECT_EQ(v.odd, 0);
    }
  }
  EXPECT_EQ(interior, 49);
  EXPECT_EQ(corners, 4);
  EXPECT_EQ(edgeVertices, 28);
  EXPECT_EQ(odd, 16);  // 4 per edge
  EXPECT_FALSE(buildPatchMesh(0));
  EXPECT_FALSE(buildPatchMesh(12));
}

TEST(PatchMesh, StitchingFollowsTheLookUpForEveryOrientationAndEdge) {
  for (int cells : {2, 8, 64}) {
    Result<PatchMesh> mesh = buildPatchMesh(cells);
    ASSERT_TRUE(mesh);
    for (int o = 0; o <= int(PatchOrientation::NorthWest); ++o) {
      const std::uint8_t stitch = outwardEdges(PatchOrientation(o));
      for (std::uint8_t edge : kEdges) {
        std::set<std::pair<int, int>> expected;
        const int step = (stitch & edge) != 0 ? 2 : 1;  // the coarser neighbour's spacing
        for (int a = 0; a < cells; a += step) expected.insert({a, a + step});
        EXPECT_EQ(edgeSegments(mesh.value(), stitch, edge), expected)
            << "cells " << cells << " orientation " << o << " edge " << int(edge);
        // Every vertex of a stitched edge sits on an even position.
        for (const PatchVertex& v : mesh->vertices) {
          const int a = alongEdge(stitchedPosition(v, stitch), edge, cells);
          if (a >= 0 && (stitch & edge) != 0) {
            EXPECT_EQ(a % 2, 0);
          }
        }
      }
    }
  }
}

TEST(PatchMesh, InteriorVerticesNeverMove) {
  Result<PatchMesh> mesh = buildPatchMesh(16);
  ASSERT_TRUE(mesh);
  for (const PatchVertex& v : mesh->vertices) {
    if (v.edges != 0) continue;
    EXPECT_EQ(stitchedPosition(v, kEdgeUp | kEdgeRight | kEdgeDown | kEdgeLeft),
              glm::ivec2(v.x, v.z));
  }
}

}  // namespace
}  // namespace tellus
