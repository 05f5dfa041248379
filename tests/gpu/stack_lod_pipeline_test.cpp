// The quadrangulation pipeline's octree mode on the GPU (StackQuadPipelineGpu::countBatch and
// writeBatch): every level at once, stitched nodes, meshes written at the caller's places,
// against the CPU reference (lod/stacks/stitched_quadrangulation.hpp) cell for cell, and the
// whole selection closed.
#include <gtest/gtest.h>

#include <cmath>

#include "support/gl_test.hpp"
#include "support/stack_fixtures.hpp"
#include "tellus/lod/stacks/stitched_quadrangulation.hpp"
#include "tellus/render/stacks/stack_quad_pipeline.hpp"
#include "tellus/formats/stacks/dual_contouring.hpp"
#include "tellus/formats/stacks/stack_aggregation.hpp"
#include "tellus/formats/stacks/stack_generator.hpp"
#include "tellus/formats/stacks/stack_mesh_check.hpp"

namespace tellus {
namespace {

class StackLodPipelineTest : public test::GlTest {
 protected:
  // Hills with caves, 96 x 80 stacks of 4 m, cells of 2 m, nodes of 9^3 cells.
  static StackLevels levels() {
    Result<StackTerrain> terrain = test::hillsWithCaves({});
    EXPECT_TRUE(terrain) << terrain.error().message;
    QuadParams params;
    params.nodeCells = 9;
    Result<StackLevels> levels =
        StackLevels::build(buildStackPyramid(std::move(terrain.value())), 2.0, params);
    EXPECT_TRUE(levels) << levels.error().message;
    return std::move(levels.value());
  }
};

TEST_F(StackLodPipelineTest, StitchedNodesMatchTheCpuReferenceAndCloseTheSurface) {
  const StackLevels stackLevels = levels();
  const StackOctree octree(stackLevels);
  SelectionView view;
  view.camera = {40.0, 60.0, 90.0};
  view.fovYDeg = 60.0;
  view.viewportHeightPx = 720;
  view.tauPx = 60.0;
  const StackSelection selection = selectStackNodes(octree, view);
  ASSERT_GT(selection.nodes.size(), 20u);
  Result<StackQuadPipelineGpu> gpu = StackQuadPipelineGpu::create(stackLevels, 16);
  ASSERT_TRUE(gpu) << gpu.error().message;
  const int n = stackLevels.params().nodeCells;
  const std::size_t cellCount = std::size_t(n) * n * n;

  StackMesh all;  // the GPU's meshes, rebased into one mesh
  std::size_t stitched = 0, comparedQuads = 0, morphing = 0;
  for (std::size_t first = 0; first < selection.nodes.size(); first += 16) {
    const std::size_t size = std::min<std::size_t>(16, selection.nodes.size() - first);
    std::vector<StackQuadPipelineGpu::NodeJob> jobs;
    for (std::size_t i = 0; i < size; ++i) {
      const SelectedNode& node = selection.nodes[first + i];
      const StitchGeometry geometry = StitchGeometry::of(octree, node.key, node.stitchMask);
      jobs.push_back({octree.origin(node.key), node.key.level, geometry.parentFirst, node.stitchMask});
    }
    Result<std::vector<StackQuadPipelineGpu::NodeCounts>> counts = gpu->countBatch(jobs);
    ASSERT_TRUE(counts) << counts.error().message;
    // Place the nodes one after another, after a gap, as a pool would.
    std::vector<std::array<std::uint32_t, 2>> firsts;
    std::uint32_t vertices = 7, indices = 12;
    for (const auto& c : counts.value()) {
      firsts.push_back({vertices, indices});
      vertices += c.vertices;
      indices += c.indices;
    }
    gl::Buffer vertexBuffer(std::size_t(vertices) * sizeof(StackVertex), nullptr);
    gl::Buffer indexBuffer(std::size_t(indices) * 4, nullptr);
    gl::Buffer targetBuffer(std::size_t(vertices) * sizeof(MorphTarget), nullptr);
    gpu->writeBatch(firsts, vertexBuffer, vertices, indexBuffer, indices, &targetBuffer);
    std::vector<MorphTarget> gpuTargets(vertices);
    targetBuffer.download(0, gpuTargets.size() * sizeof(MorphTarget), gpuTargets.data());
    std::vector<StackVertex> gpuVertices(vertices);
    std::vector<std::uint32_t> gpuIndices(indices);
    vertexBuffer.download(0, gpuVertices.size() * sizeof(StackVertex), gpuVertices.data());
    indexBuffer.download(0, gpuIndices.size() * 4, gpuIndices.data());
    for (std::size_t i = 0; i < size; ++i) {
      const SelectedNode& node = selection.nodes[first + i];
      if (node.stitchMask != 0u) ++stitched;
      StackMesh cpu;
      std::vector<CellEntry> cpuCells;
      StitchStats stats;
      std::vector<MorphTarget> cpuTargets;
      quadrangulateStitchedNode(octree, node.key, node.stitchMask, cpu, &cpuCells, &stats,
                                &cpuTargets);
      ASSERT_EQ(cpuTargets.size(), cpu.vertices.size());
      ASSERT_EQ(stats.faults, 0u);
      ASSERT_EQ(counts.value()[i].vertices, cpu.vertices.size());
      ASSERT_EQ(counts.value()[i].indices, cpu.indices.size());
      const std::vector<CellEntry> gpuCells = gpu->readCells(int(i));
      // The GPU numbers rows in the order its atomics ran: map through the cell tables.
      std::vector<std::uint32_t> toGpu(cpu.vertices.size(), ~0u);
      for (std::size_t c = 0; c < cellCount; ++c) {
        ASSERT_EQ(gpuCells[c].code, cpuCells[c].code) << "cell " << c;
        if (!dc::codeHasVertex(cpuCells[c].code)) continue;
        toGpu[cpuCells[c].vertexIndex] = gpuCells[c].vertexIndex;
        const StackVertex& a = cpu.vertices[cpuCells[c].vertexIndex];
        const StackVertex& b = gpuVertices[firsts[i][0] + gpuCells[c].vertexIndex];
        const MorphTarget& ta = cpuTargets[cpuCells[c].vertexIndex];
        const MorphTarget& tb = gpuTargets[firsts[i][0] + gpuCells[c].vertexIndex];
        for (int k = 0; k < 3; ++k) {
          ASSERT_NEAR(a.position[std::size_t(k)], b.position[std::size_t(k)], 1e-3f) << "cell " << c;
          ASSERT_NEAR(a.normal[std::size_t(k)], b.normal[std::size_t(k)], 1e-3f) << "cell " << c;
          ASSERT_NEAR(ta[std::size_t(k)], tb[std::size_t(k)], 1e-3f) << "target, cell " << c;
        }
        ASSERT_EQ(ta[3], tb[3]) << "border bits, cell " << c;
        if (ta[0] != a.position[0] || ta[1] != a.position[1] || ta[2] != a.position[2]) ++morphing;
      }
      for (std::size_t c = 0; c < cellCount; ++c) {
        const int quads = std::popcount(dc::codeQuads(cpuCells[c].code));
        for (int q = 0; q < 6 * quads; ++q) {
          const std::uint32_t cpuIndex = cpu.indices[cpuCells[c].indexOffset + std::size_t(q)];
          const std::uint32_t gpuIndex = gpuIndices[firsts[i][1] + gpuCells[c].indexOffset + std::size_t(q)];
          ASSERT_EQ(toGpu[cpuIndex], gpuIndex) << "cell " << c << " index " << q;
        }
        comparedQuads += std::size_t(quads);
      }
      // Into the combined mesh.
      const auto base = std::uint32_t(all.vertices.size());
      all.vertices.insert(all.vertices.end(), gpuVertices.begin() + firsts[i][0],
                          gpuVertices.begin() + firsts[i][0] + counts.value()[i].vertices);
      for (std::uint32_t k = 0; k < counts.value()[i].indices; ++k) {
        all.indices.push_back(base + gpuIndices[firsts[i][1] + k]);
      }
    }
  }
  EXPECT_GT(stitched, 0u);
  EXPECT_GT(comparedQuads, 1000u);
  EXPECT_GT(morphing, 1000u);  // vertices whose target is not themselves
  const StackMeshCheck check = checkStackMesh(all);
  EXPECT_EQ(check.unbalancedEdges, 0u);
}

TEST_F(StackLodPipelineTest, RejectsBadBatches) {
  const StackLevels stackLevels = levels();
  Result<StackQuadPipelineGpu> gpu = StackQuadPipelineGpu::create(stackLevels, 2);
  ASSERT_TRUE(gpu);
  std::vector<StackQuadPipelineGpu::NodeJob> three(3);
  EXPECT_FALSE(gpu->countBatch(three));
  EXPECT_FALSE(gpu->countBatch({}));
}

}  // namespace
}  // namespace tellus
