// The RAG renderer (seed 004) against its CPU reference: the transform feedback output of the
// refinement passes equals rag::refine() triangle for triangle, for both variants, with and
// without early clipping; the buffers grow instead of truncating the mesh.
#include <algorithm>
#include <cstdio>
#include <memory>
#include <vector>

#include <gtest/gtest.h>

#include "support/gl_test.hpp"
#include "support/terrain_fixtures.hpp"
#include "tellus/dem/terrain_generator.hpp"
#include "tellus/eval/camera_path.hpp"
#include "tellus/eval/path_benchmark.hpp"
#include "tellus/lod/rag/rag_height_map.hpp"
#include "tellus/lod/rag/rag_mesh_check.hpp"
#include "tellus/lod/rag/rag_refinement.hpp"
#include "tellus/render/rag/rag_renderer.hpp"

namespace tellus {
namespace {

using RagRendererTest = test::GlTest;

HeightGrid smallTerrain(int size = 129) {
  TerrainParams params;
  params.size = size;
  params.seed = 3;
  params.spacingM = 30.0;
  params.reliefM = 900.0;
  return generateTerrain(params);
}

ViewSetup obliqueView(const HeightGrid& grid, double yawDeg) {
  const Aabb bounds = grid.worldBounds();
  Camera camera;
  camera.position = {bounds.size().x * 0.3, bounds.size().y * 0.2, bounds.max.z + 200.0};
  camera.yawDeg = yawDeg;
  camera.pitchDeg = -25.0;
  camera.fovYDeg = 55.0;
  return ViewSetup::create(camera, bounds, 256, 192);
}

std::unique_ptr<RagRenderer> createRag(const HeightGrid& grid, const RagOptions& options) {
  Result<std::unique_ptr<RagRenderer>> renderer = RagRenderer::create(grid, options);
  EXPECT_TRUE(renderer.ok()) << (renderer.ok() ? "" : renderer.error().message);
  return renderer.ok() ? std::move(renderer.value()) : nullptr;
}

bool sameTriangle(const rag::Triangle& a, const rag::Triangle& b) {
  return a.v[0] == b.v[0] && a.v[1] == b.v[1] && a.v[2] == b.v[2];
}

TEST_F(RagRendererTest, TransformFeedbackOutputEqualsTheCpuReference) {
  const HeightGrid grid = smallTerrain();
  int compared = 0;
  for (const rag::Variant variant : {rag::Variant::Oblique, rag::Variant::RightAngled}) {
    for (const bool earlyClip : {false, true}) {
      for (int passes = 1; passes <= 3; ++passes) {
       for (const float morphBand : {0.0f, 1.0f}) {
       for (const int probes : {1, 3}) {
        if (variant == rag::Variant::RightAngled && (morphBand > 0.0f || probes > 1)) continue;
        SCOPED_TRACE(::testing::Message()
                     << (variant == rag::Variant::Oblique ? "rag" : "rag-right") << ", clip "
                     << earlyClip << ", " << passes << " passes, morph " << morphBand << ", "
                     << probes << " probes");
        RagOptions options;
        options.coarseVertices = 9;
        options.passes = passes;
        options.refinement.variant = variant;
        options.refinement.pixelEdge = 3.0f;
        options.refinement.heightDifferenceM = 25.0f;
        options.refinement.earlyClip = earlyClip;
        options.refinement.morphBand = morphBand;
        options.refinement.edgeProbes = probes;
        std::unique_ptr<RagRenderer> renderer = createRag(grid, options);
        ASSERT_TRUE(renderer);
        const ViewSetup view = obliqueView(grid, 35.0);
        const rag::RefinementView cpuView = rag::RefinementView::create(view, grid, 1.0f);
        const rag::RefinementResult cpu =
            rag::refine(renderer->coarseMesh(), grid, cpuView, renderer->refinement(), passes);
        // A decision within 1e-4 of its threshold could round either way in float.
        ASSERT_GT(cpu.closestDecision, 1e-4f) << "choose other thresholds for this test";
        const std::vector<rag::Triangle> gpu = renderer->refineAndRead(view, 1.0f);
        ASSERT_EQ(gpu.size(), cpu.triangles.size());
        for (std::size_t i = 0; i < gpu.size(); ++i) {
          ASSERT_TRUE(sameTriangle(gpu[i], cpu.triangles[i])) << "triangle " << i;
        }
        EXPECT_EQ(renderer->lastCounts().written[std::size_t(passes - 1)], gpu.size());
        const rag::MeshCheck check = rag::checkMesh(gpu);
        EXPECT_EQ(check.visibleTVertices, 0u);
        if (variant == rag::Variant::Oblique) {
          EXPECT_EQ(check.tVertices, 0u);
        }
        ++compared;
       }
       }
      }
    }
  }
  EXPECT_EQ(compared, 30);
}

// The aligned coarse mesh (the default): heights from the reference's triangles, the other
// diagonal of single cells split, and edges long for their distance split without probing,
// on the GPU as on the CPU, from a camera a few metres above the ground.
TEST_F(RagRendererTest, AlignedRefinementNearTheGroundEqualsTheCpuReference) {
  const HeightGrid grid = smallTerrain();
  int compared = 0;
  for (const float edgeLengthPx : {0.0f, 40.0f}) {
    for (int passes = 3; passes <= 5; ++passes) {
      SCOPED_TRACE(::testing::Message() << edgeLengthPx << " px edges, " << passes << " passes");
      RagOptions options;
      options.coarseVertices = 9;  // cells of 16 samples: 4 passes to single samples, 1 more
      options.alignCoarseMesh = true;
      options.passes = passes;
      options.refinement.pixelEdge = 0.7f;
      options.refinement.edgeLengthPx = edgeLengthPx;
      std::unique_ptr<RagRenderer> renderer = createRag(grid, options);
      ASSERT_TRUE(renderer);
      ASSERT_EQ(renderer->refinement().sampling, rag::MapSampling::Surface);
      const Aabb bounds = grid.worldBounds();
      Camera camera;
      camera.position = {bounds.size().x * 0.4, bounds.size().y * 0.3, 0.0};
      camera.position.z = grid.meshHeightAtWorld(camera.position.x, camera.position.y) + 3.0;
      camera.yawDeg = 30.0;
      camera.pitchDeg = -5.0;
      camera.fovYDeg = 60.0;
      const ViewSetup view = ViewSetup::create(camera, bounds, 256, 192);
      const rag::RefinementResult cpu =
          rag::refine(renderer->coarseMesh(), grid, rag::RefinementView::create(view, grid, 1.0f),
                      renderer->refinement(), passes);
      ASSERT_GT(cpu.closestDecision, 1e-4f) << "choose other thresholds for this test";
      const std::vector<rag::Triangle> gpu = renderer->refineAndRead(view, 1.0f);
      ASSERT_EQ(gpu.size(), cpu.triangles.size());
      for (std::size_t i = 0; i < gpu.size(); ++i) {
        ASSERT_TRUE(sameTriangle(gpu[i], cpu.triangles[i])) << "triangle " << i;
      }
      const rag::MeshCheck check = rag::checkMesh(gpu);
      EXPECT_EQ(check.tVertices, 0u);
      EXPECT_EQ(check.heightConflicts, 0u);
      ++compared;
    }
  }
  EXPECT_EQ(compared, 6);
}

TEST_F(RagRendererTest, BuffersGrowInsteadOfTruncatingTheMesh) {
  const HeightGrid grid = smallTerrain(513);
  RagOptions options;
  options.coarseVertices = 33;  // 2048 triangles of 16 x 16 samples
  options.passes = 3;
  options.refinement.variant = rag::Variant::RightAngled;
  options.refinement.heightDifferenceM = 0.0f;  // split every edge that is not flat
  options.refinement.depthDetail = 1.0f;
  options.refinement.earlyClip = false;
  std::unique_ptr<RagRenderer> renderer = createRag(grid, options);
  ASSERT_TRUE(renderer);
  const std::uint64_t initialCapacity = renderer->capacityTriangles();
  const ViewSetup view = obliqueView(grid, 35.0);
  const rag::RefinementResult cpu = rag::refine(
      renderer->coarseMesh(), grid, rag::RefinementView::create(view, grid, 1.0f),
      options.refinement, options.passes);
  ASSERT_GT(cpu.triangles.size(), initialCapacity) << "the test must overflow the buffers";

  // Drawing without exact counts: the first frame overflows and is counted when its queries
  // are read in the next frame, which refines in grown buffers.
  for (int frame = 0; frame < 4; ++frame) {
    test::renderFrame(*renderer, grid.worldBounds(), view.camera, view.width, view.height);
  }
  EXPECT_EQ(renderer->overflowedFrames(), 1u);
  // The benchmark learns which frame it was: finishStats() after the frame flags it.
  std::unique_ptr<RagRenderer> timed = createRag(grid, options);
  ASSERT_TRUE(timed);
  for (const bool expectTruncated : {true, false}) {
    test::renderFrame(*timed, grid.worldBounds(), view.camera, view.width, view.height);
    FrameStats stats;
    timed->finishStats(stats);
    EXPECT_EQ(stats.truncated, expectTruncated);
    EXPECT_EQ(stats.triangles, expectTruncated ? timed->lastCounts().written[2]
                                               : cpu.triangles.size());
  }
  EXPECT_GE(renderer->capacityTriangles(), cpu.triangles.size());
  EXPECT_EQ(renderer->lastCounts().written[2], cpu.triangles.size());

  // With exact counts nothing is ever drawn truncated: the frame is refined again.
  options.exactCounts = true;
  std::unique_ptr<RagRenderer> exact = createRag(grid, options);
  ASSERT_TRUE(exact);
  const std::vector<rag::Triangle> mesh = exact->refineAndRead(view, 1.0f);
  EXPECT_EQ(mesh.size(), cpu.triangles.size());
  EXPECT_GT(exact->capacityTriangles(), initialCapacity);
}

// Refinement is deterministic, so redrawing the previous frame's selection under a still camera
// gives the same surface (popping exactly 0); when the camera moves, the mesh it refines for
// changes and the metric sees it.
TEST_F(RagRendererTest, PoppingIsZeroForAStillCameraAndShowsWhenItMoves) {
  const HeightGrid grid = smallTerrain();
  RagOptions options;
  options.coarseVertices = 9;
  options.passes = 4;
  options.refinement.pixelEdge = 0.5f;
  // The seed's mesh, which pops when the camera moves (the aligned default pops a tenth as much
  // on this descent).
  options.alignCoarseMesh = false;
  options.refinement.edgeLengthPx = 0.0f;
  std::unique_ptr<RagRenderer> renderer = createRag(grid, options);
  ASSERT_TRUE(renderer);
  const PathRunOptions run = test::qualityRun(256, 192, 1);
  const std::vector<Camera> still(3, obliqueView(grid, 30.0).camera);
  Result<PathRun> stillRun = runPath(*renderer, still, grid, run);
  ASSERT_TRUE(stillRun) << stillRun.error().message;
  for (const FrameRecord& f : stillRun->frames) {
    EXPECT_GT(f.popPixels, 5000u) << f.index;
    EXPECT_EQ(f.popPxMax, 0.0) << f.index;
  }
  std::vector<Camera> moving;
  for (int i = 0; i < 3; ++i) {
    Camera camera = obliqueView(grid, 30.0).camera;
    camera.position.z -= 120.0 * i;  // lower, so nearer the ground: finer refinement
    camera.position.x += 150.0 * i;
    moving.push_back(camera);
  }
  Result<PathRun> movingRun = runPath(*renderer, moving, grid, run);
  ASSERT_TRUE(movingRun) << movingRun.error().message;
  // Both moves change the mesh; the second, nearer the ground, by pixels.
  EXPECT_GT(movingRun->frames[1].popPxMax, 0.1);
  EXPECT_GT(movingRun->frames[2].popPxMax, 0.1);
  EXPECT_GT(std::max(movingRun->frames[1].popPxMax, movingRun->frames[2].popPxMax), 1.0);
}

// The morph band (RefinementSettings::morphBand): a descent in small steps splits edges in every
// frame; with the band the new vertices rise from their edges' midpoints instead of jumping to
// the map's height, so each frame moves the surface less, with no crack.
TEST_F(RagRendererTest, MorphingNewVerticesPopsLessThanSplittingAtOnce) {
  const HeightGrid grid = smallTerrain();
  std::vector<Camera> descent;
  for (int i = 0; i < 12; ++i) {
    Camera camera = obliqueView(grid, 30.0).camera;
    camera.position.z -= 12.0 * i;
    camera.position.x += 15.0 * i;
    descent.push_back(camera);
  }
  const PathRunOptions run = test::qualityRun(256, 192, 1);
  const auto fly = [&](float morphBand, int probes) {
    RagOptions options;
    options.coarseVertices = 9;
    options.passes = 6;
    options.refinement.pixelEdge = 1.0f;
    options.refinement.morphBand = morphBand;
    options.refinement.edgeProbes = probes;
    options.alignCoarseMesh = false;  // the seed's mesh: its splits pop (the aligned one hardly)
    options.refinement.edgeLengthPx = 0.0f;
    std::unique_ptr<RagRenderer> renderer = createRag(grid, options);
    EXPECT_TRUE(renderer);
    Result<PathRun> result = runPath(*renderer, descent, grid, run);
    EXPECT_TRUE(result) << result.error().message;
    return std::move(result.value());
  };
  // The seed's midpoint test, and the quarter points too (the default). With the quarter points
  // an edge splits on a larger error than its midpoint's, so its new vertex rises over more
  // frames: the worst frame pops less, but the frames' means no longer add up to less.
  for (const int probes : {1, 3}) {
    SCOPED_TRACE(::testing::Message() << probes << " probes");
    const PathRun once = fly(0.0f, probes), morphed = fly(1.0f, probes);
    double worstOnce = 0.0, worstMorphed = 0.0, sumOnce = 0.0, sumMorphed = 0.0;
    std::uint64_t cracks = 0;
    for (std::size_t f = 1; f < once.frames.size(); ++f) {
      worstOnce = std::max(worstOnce, once.frames[f].popPxP99);
      worstMorphed = std::max(worstMorphed, morphed.frames[f].popPxP99);
      sumOnce += once.frames[f].popPxMean;
      sumMorphed += morphed.frames[f].popPxMean;
      cracks += once.frames[f].crackPixels + morphed.frames[f].crackPixels;
    }
    std::printf("rag, %d probes: popping p99, worst frame: %.3f px at once, %.3f px morphed; mean summed %.3f / %.3f px\n",
                probes, worstOnce, worstMorphed, sumOnce, sumMorphed);
    EXPECT_EQ(cracks, 0u);
    ASSERT_GT(worstOnce, 0.2);
    EXPECT_LT(worstMorphed, 0.7 * worstOnce);
    if (probes == 1) {
      EXPECT_LT(sumMorphed, sumOnce);
    }
  }
}

// A terrain beyond the height-map limit is refined against the finest level that fits: no
// cracks, and the measured error stays within the level's geometric error plus what RAG adds.
TEST_F(RagRendererTest, ATerrainBeyondTheTextureLimitUsesACoarserLevel) {
  const HeightGrid grid = smallTerrain(257);
  RagOptions options;
  options.coarseVertices = 9;
  options.passes = 6;
  options.exactCounts = true;
  options.maxMapSamples = 100;  // 257 a side does not fit; level 2 (65) is the finest that does
  std::unique_ptr<RagRenderer> renderer = createRag(grid, options);
  ASSERT_TRUE(renderer);
  EXPECT_EQ(renderer->mapLevel(), 2);
  EXPECT_FLOAT_EQ(renderer->mapErrorM(), rag::heightMapAtLevel(grid, 2).errorM);
  EXPECT_GT(renderer->mapErrorM(), 1.0f);

  std::vector<Camera> cameras;
  for (double yaw : {0.0, 40.0, 80.0}) cameras.push_back(obliqueView(grid, yaw).camera);
  const PathRunOptions run = test::qualityRun(256, 192, 0);
  Result<PathRun> result =
      runPath(*renderer, cameras, grid, run, test::referenceCoverage(grid, cameras, run));
  ASSERT_TRUE(result) << result.error().message;
  for (const FrameRecord& f : result->frames) {
    EXPECT_EQ(f.crackPixels, 0u) << f.index;
    EXPECT_GT(f.ssePixels, 10000u) << f.index;
  }
  // The same renderer with the whole grid is more accurate.
  options.maxMapSamples = 0;
  std::unique_ptr<RagRenderer> full = createRag(grid, options);
  ASSERT_TRUE(full);
  EXPECT_EQ(full->mapLevel(), 0);
  Result<PathRun> fullResult = runPath(*full, cameras, grid, run);
  ASSERT_TRUE(fullResult);
  EXPECT_LT(fullResult->errors.mean(), result->errors.mean());
}

// The walk (2 m above the ground) on a generated range at the defaults: SSE p99 under a pixel,
// popping p99 under half a pixel, no crack. The seed's mesh (unaligned, nearest samples, 4-8
// diagonals) is tens to hundreds of pixels off there.
TEST_F(RagRendererTest, WalksOnTheReferencesSurfaceAtTheDefaults) {
  TerrainParams params;
  params.size = 513;
  params.seed = 21;
  params.spacingM = 100.0;
  params.reliefM = 2000.0;
  const HeightGrid grid = generateTerrain(params);
  Result<CameraPath> path = makeCameraPath("walk", grid);
  ASSERT_TRUE(path) << path.error().message;
  const std::vector<Camera> cameras = path->sample(8);
  const PathRunOptions run = test::qualityRun(480, 270, 0);
  const CoverageMasks coverage = test::referenceCoverage(grid, cameras, run);
  const auto walk = [&](bool aligned) {
    RagOptions options;
    options.alignCoarseMesh = aligned;
    if (!aligned) options.passes = 6;  // the seed's mesh and passes
    std::unique_ptr<RagRenderer> renderer = createRag(grid, options);
    EXPECT_TRUE(renderer);
    Result<PathRun> result = runPath(*renderer, cameras, grid, run, coverage);
    EXPECT_TRUE(result) << result.error().message;
    for (const FrameRecord& f : result->frames) {
      EXPECT_EQ(f.crackPixels, 0u) << "aligned " << aligned << ", frame " << f.index;
    }
    return std::move(result.value());
  };
  const PathRun aligned = walk(true), seed = walk(false);
  std::printf("rag walk: SSE p99 %.2f px, popping p99 %.2f px (the seed's mesh: %.1f px, %.2f px)\n",
              aligned.errors.percentile(0.99), aligned.popping.percentile(0.99),
              seed.errors.percentile(0.99), seed.popping.percentile(0.99));
  EXPECT_LE(aligned.errors.percentile(0.99), 1.0);
  EXPECT_LE(aligned.popping.percentile(0.99), 0.5);
  EXPECT_GT(seed.errors.percentile(0.99), 5.0);
}

TEST_F(RagRendererTest, RefusesOptionsOutOfRange) {
  const HeightGrid grid = smallTerrain();
  RagOptions options;
  options.passes = kRagMaxPasses + 1;
  EXPECT_FALSE(RagRenderer::create(grid, options).ok());
  options = {};
  options.refinement.pixelEdge = 0.0f;
  EXPECT_FALSE(RagRenderer::create(grid, options).ok());
  options = {};
  options.refinement.depthDetail = 1.5f;
  EXPECT_FALSE(RagRenderer::create(grid, options).ok());
  options = {};
  options.coarseVertices = 1;
  EXPECT_FALSE(RagRenderer::create(grid, options).ok());
  options = {};
  options.refinement.edgeProbes = 2;
  EXPECT_FALSE(RagRenderer::create(grid, options).ok());
}

}  // namespace
}  // namespace tellus
