// RAG's GL-free parts (seed 004): the coarse mesh, the eight tessellations of both variants,
// the edge decisions, early clipping and the refinement loop, checked for the properties the
// GPU renderer relies on (no T-junction, no visible T-vertex, nothing visible clipped).
#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <vector>

#include <gtest/gtest.h>
#include <glm/geometric.hpp>

#include "tellus/core/camera.hpp"
#include "tellus/dem/terrain_generator.hpp"
#include "tellus/lod/rag/rag_height_map.hpp"
#include "tellus/lod/rag/rag_mesh.hpp"
#include "tellus/lod/rag/rag_mesh_check.hpp"
#include "tellus/lod/rag/rag_refinement.hpp"
#include "tellus/lod/rag/rag_tessellation.hpp"

namespace tellus::rag {
namespace {

// Twice the signed area in (u, v): positive for counter-clockwise seen from above.
float signedArea2(const Triangle& t) {
  const glm::vec2 a(t.v[1] - t.v[0]), b(t.v[2] - t.v[0]);
  return a.x * b.y - a.y * b.x;
}

bool rightAngleAtVertex0(const Triangle& t) {
  const glm::vec2 a(t.v[1] - t.v[0]), b(t.v[2] - t.v[0]);
  return a.x * b.x + a.y * b.y == 0.0f;
}

HeightGrid rampGrid(int size) {
  HeightGrid grid(size, size);
  for (int row = 0; row < size; ++row) {
    for (int col = 0; col < size; ++col) grid.at(col, row) = float(col * 3 + row * 7 % 11);
  }
  grid.spacingXM = grid.spacingYM = 10.0;
  return grid;
}

HeightGrid generatedGrid() {
  TerrainParams params;
  params.size = 257;
  params.seed = 7;
  params.spacingM = 30.0;
  params.reliefM = 1500.0;
  return generateTerrain(params);
}

Camera cameraAt(const glm::dvec3& position, double yawDeg, double pitchDeg, double fovYDeg) {
  Camera camera;
  camera.position = position;
  camera.yawDeg = yawDeg;
  camera.pitchDeg = pitchDeg;
  camera.fovYDeg = fovYDeg;
  return camera;
}

// A camera over the south-west part of the terrain looking north-east and down, so that some
// of the terrain is near, some far and some outside the view.
ViewSetup obliqueView(const HeightGrid& grid, double yawDeg = 40.0) {
  Camera camera;
  const Aabb bounds = grid.worldBounds();
  camera.position = {bounds.size().x * 0.3, bounds.size().y * 0.25, bounds.max.z + 300.0};
  camera.yawDeg = yawDeg;
  camera.pitchDeg = -20.0;
  camera.fovYDeg = 50.0;
  return ViewSetup::create(camera, bounds, 320, 240);
}

TEST(RagMesh, CoarseMeshIsRightTrianglesInTheSeedsVertexOrder) {
  const HeightGrid grid = rampGrid(65);
  const auto mesh = buildCoarseMesh(grid, 5);
  ASSERT_TRUE(mesh.ok()) << mesh.error().message;
  ASSERT_EQ(mesh->size(), 2u * 4u * 4u);
  double area = 0.0;
  for (const Triangle& t : *mesh) {
    EXPECT_GT(signedArea2(t), 0.0f);
    EXPECT_TRUE(rightAngleAtVertex0(t));
    // The hypotenuse (v1-v2) is the longest edge.
    EXPECT_GT(glm::length(glm::vec2(t.v[2] - t.v[1])), glm::length(glm::vec2(t.v[1] - t.v[0])));
    for (const Vertex& p : t.v) EXPECT_EQ(p.z, sampleNearest(grid, p.x, p.y));
    area += signedArea2(t) * 0.5;
  }
  EXPECT_DOUBLE_EQ(area, 64.0 * 64.0);
}

TEST(RagMesh, RefusesNonsenseSizes) {
  const HeightGrid grid = rampGrid(65);
  EXPECT_FALSE(buildCoarseMesh(grid, 1).ok());
  EXPECT_FALSE(buildCoarseMesh(grid, kMaxCoarseVertices + 1).ok());
  EXPECT_FALSE(buildCoarseMesh(HeightGrid(1, 5), 5).ok());
}

TEST(RagMesh, SamplesTheNearestHeightClampedToTheGrid) {
  HeightGrid grid(3, 2);  // row 0 is north
  grid.heights = {1, 2, 3, 4, 5, 6};
  EXPECT_EQ(sampleNearest(grid, 0.0f, 0.0f), 4.0f);   // south-west
  EXPECT_EQ(sampleNearest(grid, 1.49f, 0.2f), 5.0f);
  EXPECT_EQ(sampleNearest(grid, 1.5f, 0.5f), 3.0f);   // halves round up: column 2, north row
  EXPECT_EQ(sampleNearest(grid, -7.0f, 9.0f), 1.0f);  // clamped to the north-west
}

// The eight cases of both variants on one right triangle.
class RagTessellation : public ::testing::TestWithParam<Variant> {};

TEST_P(RagTessellation, EveryCaseCoversTheTriangleWithTheSeedsOrder) {
  const Variant variant = GetParam();
  HeightGrid grid(9, 9);
  for (std::size_t i = 0; i < grid.heights.size(); ++i) grid.heights[i] = float(i % 7) * 5.0f;
  const Triangle parent{{Vertex(0, 0, 1), Vertex(8, 0, 9), Vertex(0, 8, 21)}};
  const std::array<int, 8> obliqueCounts{1, 2, 2, 3, 2, 3, 3, 4};
  // Right-angled: a leg without the hypotenuse adds a fill triangle for the invisible T-vertex.
  const std::array<int, 8> rightCounts{1, 4, 2, 3, 4, 5, 3, 4};
  for (std::uint32_t needed = 0; needed < 8; ++needed) {
    SCOPED_TRACE(::testing::Message() << "case " << needed);
    const Tessellation tess = tessellate(parent, needed, variant, grid);
    const int expected = variant == Variant::Oblique ? obliqueCounts[needed] : rightCounts[needed];
    ASSERT_EQ(tess.count, expected);
    float area = 0.0f;
    const bool hasFill = variant == Variant::RightAngled && (needed & (kEdge01 | kEdge02)) != 0 &&
                         (needed & kEdge12) == 0;
    if (hasFill) {  // the last one: the hypotenuse's ends and its midpoint, in a line
      const Triangle& fill = tess.triangles[std::size_t(tess.count - 1)];
      EXPECT_EQ(signedArea2(fill), 0.0f);
      EXPECT_EQ(fill.v[0], parent.v[1]);
      EXPECT_EQ(fill.v[2], parent.v[2]);
    }
    for (int i = 0; i < tess.count - (hasFill ? 1 : 0); ++i) {
      const Triangle& t = tess.triangles[std::size_t(i)];
      EXPECT_GT(signedArea2(t), 0.0f);
      area += signedArea2(t);
      if (variant == Variant::RightAngled || (needed & kEdge12) != 0 || needed == 0) {
        EXPECT_TRUE(rightAngleAtVertex0(t)) << "triangle " << i;
      }
    }
    EXPECT_EQ(area, signedArea2(parent));
    // Exactly the case's midpoints appear, with the heights the variant gives them.
    const std::uint32_t tess_case = tessellationCase(variant, needed);
    const std::array<std::array<int, 2>, 3> ends{{{0, 1}, {1, 2}, {0, 2}}};
    for (std::uint32_t e = 0; e < 3; ++e) {
      const Vertex& a = parent.v[std::size_t(ends[e][0])];
      const Vertex& b = parent.v[std::size_t(ends[e][1])];
      const glm::vec2 mid = (glm::vec2(a) + glm::vec2(b)) * 0.5f;
      const Vertex* found = nullptr;
      for (int i = 0; i < tess.count; ++i) {
        for (const Vertex& p : tess.triangles[std::size_t(i)].v) {
          if (glm::vec2(p) == mid) found = &p;
        }
      }
      EXPECT_EQ(found != nullptr, (tess_case & (1u << e)) != 0) << "edge " << e;
      if (found == nullptr) continue;
      const float expectedHeight = (needed & (1u << e)) != 0 ? sampleNearest(grid, mid.x, mid.y)
                                                              : (a.z + b.z) * 0.5f;
      EXPECT_EQ(found->z, expectedHeight) << "edge " << e;
    }
  }
}

INSTANTIATE_TEST_SUITE_P(BothVariants, RagTessellation,
                         ::testing::Values(Variant::Oblique, Variant::RightAngled),
                         [](const auto& variant) {
                           return variant.param == Variant::Oblique ? "Oblique" : "RightAngled";
                         });

TEST(RagTessellation, RightAngledCasesPromoteLegsToTheHypotenuse) {
  EXPECT_EQ(tessellationCase(Variant::RightAngled, kEdge01), kEdge01 | kEdge12);
  EXPECT_EQ(tessellationCase(Variant::RightAngled, kEdge02), kEdge02 | kEdge12);
  EXPECT_EQ(tessellationCase(Variant::RightAngled, kEdge01 | kEdge02), 7u);
  EXPECT_EQ(tessellationCase(Variant::RightAngled, kEdge12), kEdge12);
  for (std::uint32_t c = 0; c < 8; ++c) EXPECT_EQ(tessellationCase(Variant::Oblique, c), c);
}

TEST(RagRefinement, EdgeDecisionsAreSymmetricBitForBit) {
  const HeightGrid grid = generatedGrid();
  const ViewSetup view = obliqueView(grid);
  const RefinementView rv = RefinementView::create(view, grid, 1.0f);
  const auto mesh = buildCoarseMesh(grid, 9);
  ASSERT_TRUE(mesh.ok());
  for (const Variant variant : {Variant::Oblique, Variant::RightAngled}) {
    RefinementSettings settings;
    settings.variant = variant;
    settings.morphBand = 1.0f;
    const RefinementResult refined = refine(*mesh, grid, rv, settings, 3);
    for (const Triangle& t : refined.triangles) {
      for (int e = 0; e < 3; ++e) {
        const Vertex& a = t.v[std::size_t(e)];
        const Vertex& b = t.v[std::size_t((e + 1) % 3)];
        const EdgeMeasure ab = measureEdge(rv, settings, grid, a, b);
        const EdgeMeasure ba = measureEdge(rv, settings, grid, b, a);
        ASSERT_EQ(ab.value, ba.value);
        ASSERT_EQ(ab.split, ba.split);
        ASSERT_EQ(ab.surface, ba.surface);
      }
    }
  }
}

TEST(RagRefinement, ObliqueMeshesHaveNoTJunctionAfterOneToFourPasses) {
  const HeightGrid grid = generatedGrid();
  const auto mesh = buildCoarseMesh(grid, 9);
  ASSERT_TRUE(mesh.ok());
  for (const double yaw : {40.0, 200.0}) {
    const RefinementView rv = RefinementView::create(obliqueView(grid, yaw), grid, 1.5f);
    for (const float pixels : {2.0f, 5.0f, 20.0f}) {
      for (int passes = 1; passes <= 4; ++passes) {
       for (const float morphBand : {0.0f, 1.0f}) {
        SCOPED_TRACE(::testing::Message() << "yaw " << yaw << ", " << pixels << " px, "
                                          << passes << " passes, morph " << morphBand);
        RefinementSettings settings;
        settings.pixelEdge = pixels;
        settings.morphBand = morphBand;
        const RefinementResult refined = refine(*mesh, grid, rv, settings, passes);
        const MeshCheck check = checkMesh(refined.triangles);
        EXPECT_GT(refined.triangles.size(), 0u);
        EXPECT_EQ(check.tVertices, 0u);
        EXPECT_EQ(check.heightConflicts, 0u);
        const bool splitSomething = std::any_of(
            refined.passes.begin(), refined.passes.end(),
            [](const PassStats& pass) { return pass.output > pass.input - pass.clipped; });
        EXPECT_TRUE(splitSomething);
       }
      }
    }
  }
}

// The morph band: a split edge's midpoint enters at the interpolated height (surface 0, just past
// the threshold) and reaches the map's at surface 1; measureEdge's surface grows with the error
// from 0 at pixelEdge to 1 at pixelEdge (1 + band).
TEST(RagRefinement, AMorphedMidpointRisesFromTheEdgeToTheMap) {
  HeightGrid grid(9, 9);
  for (float& h : grid.heights) h = 100.0f;
  const Triangle t{{Vertex(0, 0, 0), Vertex(8, 0, 40), Vertex(0, 8, 0)}};
  const auto heightOf = [&](float surface) {
    const Tessellation split = tessellate(t, kEdge01, Variant::Oblique, grid, true, {surface, 1.0f, 1.0f});
    return split.triangles[0].v[1].z;  // (v0, a, v2): a is the midpoint of v0-v1
  };
  EXPECT_EQ(heightOf(0.0f), 20.0f);
  EXPECT_EQ(heightOf(0.5f), 60.0f);
  EXPECT_EQ(heightOf(1.0f), 100.0f);
  const HeightGrid terrain = generatedGrid();
  const RefinementView rv = RefinementView::create(obliqueView(terrain), terrain, 1.0f);
  RefinementSettings settings;
  settings.morphBand = 0.5f;
  const auto mesh = buildCoarseMesh(terrain, 9);
  ASSERT_TRUE(mesh.ok());
  std::size_t partial = 0;
  for (const Triangle& c : refine(*mesh, terrain, rv, settings, 3).triangles) {
    for (int e = 0; e < 3; ++e) {
      const EdgeMeasure m = measureEdge(rv, settings, terrain, c.v[std::size_t(e)], c.v[std::size_t((e + 1) % 3)]);
      if (m.decided) continue;
      const float expected = std::clamp((m.value - m.threshold) / (m.threshold * 0.5f), 0.0f, 1.0f);
      ASSERT_EQ(m.surface, expected);
      if (m.surface > 0.0f && m.surface < 1.0f) ++partial;
    }
  }
  EXPECT_GT(partial, 0u);
}

TEST(RagRefinement, RightAngledMeshesHaveOnlyInvisibleTVertices) {
  const HeightGrid grid = generatedGrid();
  const auto mesh = buildCoarseMesh(grid, 9);
  ASSERT_TRUE(mesh.ok());
  const RefinementView rv = RefinementView::create(obliqueView(grid), grid, 1.0f);
  std::uint64_t tVertices = 0;
  for (const float metres : {5.0f, 20.0f, 80.0f}) {
    for (int passes = 1; passes <= 4; ++passes) {
      SCOPED_TRACE(::testing::Message() << metres << " m, " << passes << " passes");
      RefinementSettings settings;
      settings.variant = Variant::RightAngled;
      settings.heightDifferenceM = metres;
      const RefinementResult refined = refine(*mesh, grid, rv, settings, passes);
      const MeshCheck check = checkMesh(refined.triangles);
      EXPECT_EQ(check.visibleTVertices, 0u) << "largest gap " << check.largestGapM << " m";
      EXPECT_EQ(check.heightConflicts, 0u);
      for (const Triangle& t : refined.triangles) {
        if (signedArea2(t) != 0.0f) {  // else a fill triangle
          ASSERT_TRUE(rightAngleAtVertex0(t));
        }
      }
      tVertices += check.tVertices;
    }
  }
  EXPECT_GT(tVertices, 0u) << "the forced hypotenuse splits should leave invisible T-vertices";
}

TEST(RagRefinement, AMeshCheckFindsAVisibleTVertex) {
  // Two triangles sharing the edge (8,0)-(0,8); the first one split it with a map height.
  HeightGrid grid(9, 9);
  for (float& h : grid.heights) h = 100.0f;
  const Triangle left{{Vertex(0, 0, 0), Vertex(8, 0, 0), Vertex(0, 8, 0)}};
  const Triangle right{{Vertex(8, 8, 0), Vertex(0, 8, 0), Vertex(8, 0, 0)}};
  const Tessellation split = tessellate(left, kEdge12, Variant::Oblique, grid);
  std::vector<Triangle> mesh(split.triangles.begin(), split.triangles.begin() + split.count);
  mesh.push_back(right);
  const MeshCheck check = checkMesh(mesh);
  EXPECT_EQ(check.tVertices, 1u);
  EXPECT_EQ(check.visibleTVertices, 1u);
  EXPECT_EQ(check.largestGapM, 100.0f);
}

// Sutherland-Hodgman: does the clip-space triangle keep any area inside the view volume?
bool touchesViewVolume(const std::array<glm::vec4, 3>& triangle) {
  std::vector<glm::vec4> polygon(triangle.begin(), triangle.end());
  const std::array<glm::vec4, 6> planes{glm::vec4(1, 0, 0, 1),  glm::vec4(-1, 0, 0, 1),
                                        glm::vec4(0, 1, 0, 1),  glm::vec4(0, -1, 0, 1),
                                        glm::vec4(0, 0, 1, 0),  glm::vec4(0, 0, -1, 1)};
  for (const glm::vec4& plane : planes) {
    std::vector<glm::vec4> out;
    for (std::size_t i = 0; i < polygon.size(); ++i) {
      const glm::vec4& p = polygon[i];
      const glm::vec4& q = polygon[(i + 1) % polygon.size()];
      const float dp = glm::dot(plane, p), dq = glm::dot(plane, q);
      if (dp >= 0.0f) out.push_back(p);
      if ((dp >= 0.0f) != (dq >= 0.0f)) out.push_back(p + (q - p) * (dp / (dp - dq)));
    }
    polygon = std::move(out);
    if (polygon.empty()) return false;
  }
  return true;
}

TEST(RagRefinement, EarlyClippingNeverRemovesAVisibleTriangle) {
  const HeightGrid grid = generatedGrid();
  const auto mesh = buildCoarseMesh(grid, 17);
  ASSERT_TRUE(mesh.ok());
  for (const Variant variant : {Variant::Oblique, Variant::RightAngled}) {
    for (const double yaw : {0.0, 40.0, 135.0, 250.0}) {
      SCOPED_TRACE(::testing::Message() << "yaw " << yaw);
      const RefinementView rv = RefinementView::create(obliqueView(grid, yaw), grid, 1.0f);
      RefinementSettings settings;
      settings.variant = variant;
      settings.pixelEdge = 4.0f;
      settings.earlyClip = false;
      const RefinementResult all = refine(*mesh, grid, rv, settings, 3);
      settings.earlyClip = true;
      const RefinementResult clipped = refine(*mesh, grid, rv, settings, 3);
      std::uint64_t dropped = 0;
      for (const PassStats& pass : clipped.passes) dropped += pass.clipped;
      EXPECT_GT(dropped, 0u);
      EXPECT_LT(clipped.triangles.size(), all.triangles.size());
      // Every triangle of the unclipped mesh that reaches the view volume is kept as it is.
      std::map<std::array<float, 9>, int> kept;
      for (const Triangle& t : clipped.triangles) {
        ++kept[{t.v[0].x, t.v[0].y, t.v[0].z, t.v[1].x, t.v[1].y, t.v[1].z, t.v[2].x,
                t.v[2].y, t.v[2].z}];
      }
      for (const Triangle& t : all.triangles) {
        const std::array<glm::vec4, 3> clip{clipPosition(rv, t.v[0]), clipPosition(rv, t.v[1]),
                                            clipPosition(rv, t.v[2])};
        if (!touchesViewVolume(clip)) continue;
        ASSERT_TRUE(kept.count({t.v[0].x, t.v[0].y, t.v[0].z, t.v[1].x, t.v[1].y, t.v[1].z,
                                t.v[2].x, t.v[2].y, t.v[2].z}))
            << "a visible triangle was clipped";
      }
    }
  }
}

TEST(RagRefinement, FewerPixelsAndMorePassesGiveMoreTriangles) {
  const HeightGrid grid = generatedGrid();
  const auto mesh = buildCoarseMesh(grid, 9);
  ASSERT_TRUE(mesh.ok());
  const RefinementView rv = RefinementView::create(obliqueView(grid), grid, 1.0f);
  const auto count = [&](float pixels, int passes, int probes = 1) {  // the seed's midpoint test
    RefinementSettings settings;
    settings.pixelEdge = pixels;
    settings.edgeProbes = probes;
    return refine(*mesh, grid, rv, settings, passes).triangles.size();
  };
  // The quarter points split every edge the midpoint splits, and more: one pass (a triangle
  // becomes one more triangle per split edge) makes at least as many triangles.
  EXPECT_GE(count(10.0f, 1, 3), count(10.0f, 1, 1));
  EXPECT_GT(count(40.0f, 1, 3), count(40.0f, 1, 1));
  EXPECT_LT(count(20.0f, 2), count(10.0f, 2));
  EXPECT_LT(count(10.0f, 2), count(5.0f, 2));
  EXPECT_LT(count(10.0f, 1), count(10.0f, 2));
  EXPECT_LE(count(10.0f, 2), count(10.0f, 3));
  // 0 passes: the coarse mesh as it is.
  EXPECT_EQ(count(10.0f, 0), mesh->size());
}

// The seed's midpoint test is blind to a ridge beside a midpoint that lies on the surface; the
// quarter points (edgeProbes 3) see it. A flat grid, 100 m spacing, with a 300 m ridge along the
// column a quarter of the way along an edge from u = 20 to u = 60.
TEST(RagRefinement, QuarterPointProbesSeeDetailTheMidpointMisses) {
  HeightGrid grid(81, 81);
  grid.spacingXM = grid.spacingYM = 100.0;
  for (int row = 0; row < 81; ++row) {
    for (int col = 0; col < 81; ++col) grid.at(col, row) = col == 30 ? 300.0f : 0.0f;
  }
  const ViewSetup view =
      ViewSetup::create(cameraAt({4000.0, -2000.0, 3000.0}, 0.0, -35.0, 50.0), grid.worldBounds(), 640, 480);
  const RefinementView rv = RefinementView::create(view, grid, 1.0f);
  RefinementSettings settings;
  settings.pixelEdge = 1.0f;
  const Vertex a(20, 40, 0), b(60, 40, 0);
  settings.edgeProbes = 1;
  const EdgeMeasure midpoint = measureEdge(rv, settings, grid, a, b);
  EXPECT_FALSE(midpoint.split);
  EXPECT_EQ(midpoint.value, 0.0f);
  settings.edgeProbes = 3;
  const EdgeMeasure quarters = measureEdge(rv, settings, grid, a, b);
  EXPECT_TRUE(quarters.split);
  EXPECT_GT(quarters.value, 10.0f);
  // Symmetric bit for bit with three probes too.
  EXPECT_EQ(measureEdge(rv, settings, grid, b, a).value, quarters.value);
}

TEST(RagRefinement, DepthDetailOneWeighsHeightDifferencesTheSameEverywhere) {
  const HeightGrid grid = generatedGrid();
  const auto mesh = buildCoarseMesh(grid, 9);
  ASSERT_TRUE(mesh.ok());
  const RefinementView rv = RefinementView::create(obliqueView(grid), grid, 1.0f);
  RefinementSettings settings;
  settings.variant = Variant::RightAngled;
  settings.heightDifferenceM = 30.0f;
  settings.earlyClip = false;
  const auto triangles = [&](float depthDetail) {
    settings.depthDetail = depthDetail;
    return refine(*mesh, grid, rv, settings, 3).triangles.size();
  };
  EXPECT_LT(triangles(0.0f), triangles(0.5f));
  EXPECT_LT(triangles(0.5f), triangles(1.0f));
  // With weight 1 everywhere the decision is the plain height difference.
  settings.depthDetail = 1.0f;
  const Vertex a(10, 10, 100), b(30, 10, 131);
  EXPECT_TRUE(edgeNeedsSplit(rv, settings, grid, a, b));
  EXPECT_FALSE(edgeNeedsSplit(rv, settings, grid, a, Vertex(30, 10, 129)));
  // Ends within one sample of each other are never split.
  EXPECT_FALSE(edgeNeedsSplit(rv, settings, grid, a, Vertex(11, 11, 500)));
}

TEST(RagMesh, SurfaceSamplingIsTheReferencesTriangles) {
  const HeightGrid grid = generatedGrid();
  for (int i = 0; i < 4000; ++i) {
    // Tenths of a sample over the whole grid and a little beyond (clamped), samples and cell
    // centres among them.
    const float u = float((i * 37) % 2601) / 10.0f - 2.0f;
    const float v = float((i * 53) % 2601) / 10.0f - 2.0f;
    const double expected = grid.meshHeightAtWorld(std::max(0.0f, u) * grid.spacingXM,
                                                   std::max(0.0f, v) * grid.spacingYM);
    ASSERT_NEAR(sampleSurface(grid, u, v), expected, 1e-3 * (1.0 + std::abs(expected)))
        << "at (" << u << ", " << v << ")";
  }
  for (int c = 0; c < 256; c += 17) {
    // Samples are the samples; a cell's centre lies on its south-west to north-east diagonal.
    EXPECT_EQ(sampleSurface(grid, float(c), float(c / 2)), sampleNearest(grid, float(c), float(c / 2)));
    const float sw = grid.at(c, grid.height - 1 - c / 2);
    const float ne = grid.at(c + 1, grid.height - 2 - c / 2);
    EXPECT_FLOAT_EQ(sampleSurface(grid, float(c) + 0.5f, float(c / 2) + 0.5f), (sw + ne) * 0.5f);
  }
}

// The aligned mesh refined until nothing is left to split is the reference's surface: every
// triangle lies in one of the reference's half cells. With the seed's nearest sampling the
// other diagonal of every second cell (the 4-8 bisections alternate them) stays, and the
// surface is off by metres there.
TEST(RagRefinement, AnAlignedMeshRefinedToTheEndIsTheReferencesSurface) {
  TerrainParams params;
  params.size = 65;
  params.seed = 5;
  params.spacingM = 30.0;
  params.reliefM = 800.0;
  const HeightGrid grid = generateTerrain(params);
  ASSERT_EQ(alignedCellSamples(grid, 5), 16);
  const auto mesh = buildAlignedCoarseMesh(grid, 5);
  ASSERT_TRUE(mesh.ok());
  const RefinementView rv = RefinementView::create(obliqueView(grid), grid, 1.0f);
  const auto largestDeviationM = [&](MapSampling sampling) {
    RefinementSettings settings;
    settings.sampling = sampling;
    settings.pixelEdge = 0.0f;  // split every edge with anything between its ends
    settings.earlyClip = false;
    const RefinementResult refined = refine(*mesh, grid, rv, settings, 5);  // 4 to one sample
    const MeshCheck check = checkMesh(refined.triangles);
    EXPECT_EQ(check.tVertices, 0u);
    EXPECT_EQ(check.heightConflicts, 0u);
    float largest = 0.0f;
    for (const Triangle& t : refined.triangles) {
      const Vertex centroid = (t.v[0] + t.v[1] + t.v[2]) / 3.0f;  // on the triangle's plane
      largest = std::max(largest,
                         std::abs(centroid.z - sampleSurface(grid, centroid.x, centroid.y)));
    }
    return largest;
  };
  EXPECT_LT(largestDeviationM(MapSampling::Surface), 1e-3f);
  EXPECT_GT(largestDeviationM(MapSampling::Nearest), 0.1f);
}

// Near the eye the probes can be blind (here a flat map: no probe sees anything); an edge long
// for its distance is split anyway, down to single samples under the camera, while far edges
// stay whole.
TEST(RagRefinement, EdgesLongForTheirDistanceAreSplitNearTheEye) {
  HeightGrid grid(129, 129);
  grid.spacingXM = grid.spacingYM = 30.0;
  const auto mesh = buildAlignedCoarseMesh(grid, 9);  // cells of 16 samples
  ASSERT_TRUE(mesh.ok());
  const ViewSetup view = ViewSetup::create(cameraAt({600.0, 600.0, 2.0}, 45.0, -5.0, 60.0),
                                           grid.worldBounds(), 320, 240);
  const RefinementView rv = RefinementView::create(view, grid, 1.0f);
  RefinementSettings settings;
  settings.sampling = MapSampling::Surface;
  settings.earlyClip = false;
  // The longest edge of the triangles whose bounds hold (u, v).
  const auto longestEdgeAt = [&](const RefinementResult& refined, float u, float v) {
    float longest = 0.0f;
    for (const Triangle& t : refined.triangles) {
      const glm::vec2 a(t.v[0]), b(t.v[1]), c(t.v[2]);
      const glm::vec2 lo = glm::min(glm::min(a, b), c), hi = glm::max(glm::max(a, b), c);
      if (u < lo.x || u > hi.x || v < lo.y || v > hi.y) continue;
      longest = std::max({longest, glm::length(a - b), glm::length(b - c), glm::length(c - a)});
    }
    return longest;
  };
  // 60 m ahead of the camera (yaw 45: north-east), and 3 km away to the east-south-east.
  const float aheadU = float((600.0 + 60.0 * std::sqrt(0.5)) / 30.0), aheadV = aheadU;
  settings.edgeLengthPx = 0.0f;  // the seed's: probes only
  const RefinementResult blind = refine(*mesh, grid, rv, settings, 5);
  EXPECT_GE(longestEdgeAt(blind, aheadU, aheadV), 16.0f);
  settings.edgeLengthPx = 64.0f;  // a 16-sample edge 3 km away spans 33 px face-on
  const RefinementResult refined = refine(*mesh, grid, rv, settings, 5);
  EXPECT_GT(refined.triangles.size(), blind.triangles.size());
  EXPECT_EQ(checkMesh(refined.triangles).tVertices, 0u);
  EXPECT_LE(longestEdgeAt(refined, aheadU, aheadV), 1.5f);  // single samples
  EXPECT_GE(longestEdgeAt(refined, 120.3f, 8.3f), 16.0f);   // far: left whole
}

}  // namespace
}  // namespace tellus::rag

namespace tellus {
namespace {

TEST(RagHeightMap, PicksTheFinestLevelThatFits) {
  EXPECT_EQ(rag::heightMapLevel(129, 129, 16384), 0);
  EXPECT_EQ(rag::heightMapLevel(16385, 16385, 16384), 1);  // 8193 a side
  EXPECT_EQ(rag::heightMapLevel(16385, 16385, 8192), 2);   // 8193 > 8192: 4097
  EXPECT_EQ(rag::heightMapLevel(129, 40, 65), 1);
  EXPECT_EQ(rag::heightMapLevel(4801, 4801, 1024), 3);     // 601 a side
}

// h = col^2 along the rows: the level-1 map keeps the even columns, and linear interpolation
// between columns 2k and 2k + 2 is off by exactly 1 m at the odd column between them.
TEST(RagHeightMap, KeepsTheSouthWesternSamplesAndMeasuresTheError) {
  HeightGrid grid(10, 7);  // 9 x 6 cells: one column east left out at level 1, none north
  grid.spacingXM = 30.0;
  grid.spacingYM = 20.0;
  for (int r = 0; r < grid.height; ++r)
    for (int c = 0; c < grid.width; ++c) grid.at(c, r) = float(c * c);
  const rag::HeightMap map = rag::heightMapAtLevel(grid, 1);
  EXPECT_EQ(map.level, 1);
  EXPECT_EQ(map.grid.width, 5);
  EXPECT_EQ(map.grid.height, 4);
  EXPECT_EQ(map.droppedColumns, 1);
  EXPECT_EQ(map.droppedRows, 0);
  EXPECT_DOUBLE_EQ(map.grid.spacingXM, 60.0);
  EXPECT_DOUBLE_EQ(map.grid.spacingYM, 40.0);
  for (int r = 0; r < map.grid.height; ++r)
    for (int c = 0; c < map.grid.width; ++c) EXPECT_EQ(map.grid.at(c, r), float(4 * c * c));
  EXPECT_FLOAT_EQ(map.errorM, 1.0f);

  // Rows left out are northern ones: the southern row (the world origin) stays.
  HeightGrid tall(5, 8);
  for (int r = 0; r < tall.height; ++r)
    for (int c = 0; c < tall.width; ++c) tall.at(c, r) = float(r);
  const rag::HeightMap north = rag::heightMapAtLevel(tall, 1);
  EXPECT_EQ(north.droppedRows, 1);
  EXPECT_EQ(north.grid.at(0, north.grid.height - 1), 7.0f);  // the input's southern row
  EXPECT_EQ(north.grid.at(0, 0), 1.0f);
  EXPECT_FLOAT_EQ(north.errorM, 0.0f);  // linear in the row: interpolation is exact
}

}  // namespace
}  // namespace tellus

namespace tellus {
namespace {

// Aligned coarse meshes: cells of a power of two samples, every vertex on a sample, refinement
// down to single samples with the map's own heights.
TEST(RagMesh, AlignedMeshesPutEveryVertexOnASample) {
  TerrainParams params;
  params.size = 129;
  params.seed = 4;
  const HeightGrid grid = generateTerrain(params);
  EXPECT_EQ(rag::alignedCellSamples(grid, 9), 16);  // 128 / 8 = 16 exactly
  EXPECT_EQ(rag::alignedCellSamples(grid, 11), 16);  // 12.8: nearest power of two in log scale
  HeightGrid korea(4801, 4801);
  EXPECT_EQ(rag::alignedCellSamples(korea, 80), 64);  // 60.8 -> 64: 75 cells
  const auto mesh = rag::buildAlignedCoarseMesh(grid, 9);
  ASSERT_TRUE(mesh.ok());
  EXPECT_EQ(mesh->size(), 8u * 8u * 2u);
  HeightGrid odd(130, 100);  // 129 x 99 cells: the last column and row are narrower
  const auto clamped = rag::buildAlignedCoarseMesh(odd, 9);
  ASSERT_TRUE(clamped.ok());
  EXPECT_EQ(clamped->size(), std::size_t(9 * 7 * 2));
  for (const rag::Triangle& t : *clamped) {
    for (const rag::Vertex& v : t.v) {
      EXPECT_EQ(v.x, std::floor(v.x));
      EXPECT_LE(v.x, 129.0f);
      EXPECT_LE(v.y, 99.0f);
    }
  }
  // Four passes from 16-sample cells reach single samples; every vertex on a sample, with the
  // sample's height.
  rag::RefinementSettings settings;
  settings.pixelEdge = 0.01f;
  settings.earlyClip = false;
  const ViewSetup view =
      ViewSetup::create(rag::cameraAt({1000.0, -500.0, 2500.0}, 10.0, -35.0, 60.0), grid.worldBounds(), 320, 240);
  const rag::RefinementResult refined =
      rag::refine(*mesh, grid, rag::RefinementView::create(view, grid, 1.0f), settings, 4);
  bool reachedOneSample = false;
  for (const rag::Triangle& t : refined.triangles) {
    for (const rag::Vertex& v : t.v) {
      ASSERT_EQ(v.x, std::floor(v.x));
      ASSERT_EQ(v.y, std::floor(v.y));
      ASSERT_EQ(v.z, rag::sampleNearest(grid, v.x, v.y));
    }
    reachedOneSample = reachedOneSample || std::abs(t.v[1].x - t.v[2].x) <= 1.0f;
  }
  EXPECT_TRUE(reachedOneSample);
}

}  // namespace
}  // namespace tellus
