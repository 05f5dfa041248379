// The quadrangulation pipeline on the GPU (render/stacks/stack_quad_pipeline.hpp) gives the CPU
// reference's mesh: per node the same lookup table (classification and owned quads bit for
// bit), every vertex cell's attributes within float rounding and the same quads between the
// same cells; over a whole terrain in many batches (buffers grown on the way) the same closed
// surface.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>

#include "support/gl_test.hpp"
#include "support/stack_fixtures.hpp"
#include "tellus/formats/stacks/dual_contouring.hpp"
#include "tellus/render/stacks/stack_quad_pipeline.hpp"
#include "tellus/formats/stacks/stack_generator.hpp"
#include "tellus/formats/stacks/stack_mesh_check.hpp"

namespace tellus {
namespace {

class StackQuadPipelineTest : public test::GlTest {
 protected:
  // Hills with caves, overhangs and an arch, 56 x 44 stacks of 4 m, cells of 2 m.
  static QuantisedStacks terrain() {
    Result<StackTerrain> stacks = test::hillsWithCaves(
        {.width = 56, .height = 44, .waveX = 0.2, .waveY = 0.15, .riseM = 0.8, .caveScaleM = 24.0});
    EXPECT_TRUE(stacks) << stacks.error().message;
    Result<QuantisedStacks> q = QuantisedStacks::from(stacks.value(), 2.0);
    EXPECT_TRUE(q) << q.error().message;
    return q.value();
  }

  static void expectNear(const std::array<float, 4>& a, const std::array<float, 4>& b,
                         float tolerance, const char* what, std::size_t cell) {
    for (int k = 0; k < 4; ++k) {
      ASSERT_NEAR(a[std::size_t(k)], b[std::size_t(k)], tolerance) << what << " of cell " << cell;
    }
  }

  // One node at a time: tables, attributes and quads against the CPU reference.
  static void compareNodes(const QuantisedStacks& stacks, const QuadParams& params) {
    Result<StackQuadPipelineGpu> gpu = StackQuadPipelineGpu::create(stacks, params, 1);
    ASSERT_TRUE(gpu) << gpu.error().message;
    const NodeGrid grid = NodeGrid::of(stacks, params);
    const std::vector<NodeKey> nodes = nodesWithSurface(stacks, params);
    ASSERT_GT(nodes.size(), 4u);
    std::size_t comparedQuads = 0;
    for (std::size_t n = 0; n < nodes.size(); n += 3) {  // every third node keeps it quick
      StackMesh cpu;
      std::vector<CellEntry> cpuCells;
      quadrangulateNode(stacks, params, grid.origin(nodes[n]), cpu, &cpuCells);
      ASSERT_TRUE(gpu->run(std::span(&nodes[n], 1)));
      const std::vector<CellEntry> gpuCells = gpu->readCells(0);
      const StackMesh mesh = gpu->readMesh();
      ASSERT_EQ(mesh.vertices.size(), cpu.vertices.size());
      ASSERT_EQ(mesh.indices.size(), cpu.indices.size());
      std::map<std::uint32_t, std::size_t> gpuVertexCell, cpuVertexCell;
      for (std::size_t c = 0; c < cpuCells.size(); ++c) {
        ASSERT_EQ(gpuCells[c].code, cpuCells[c].code) << "cell " << c;
        if ((cpuCells[c].code & 255u) == 0u || (cpuCells[c].code & 255u) == 255u) continue;
        gpuVertexCell[gpuCells[c].vertexIndex] = c;
        cpuVertexCell[cpuCells[c].vertexIndex] = c;
        const StackVertex& g = mesh.vertices[gpuCells[c].vertexIndex];
        const StackVertex& r = cpu.vertices[cpuCells[c].vertexIndex];
        expectNear(g.position, r.position, 2e-4f, "position", c);
        expectNear(g.normal, r.normal, 1e-5f, "normal", c);
        expectNear(g.materials, r.materials, 1e-6f, "materials", c);
      }
      for (std::size_t c = 0; c < cpuCells.size(); ++c) {
        const int quads = std::popcount(dc::codeQuads(cpuCells[c].code));
        for (int i = 0; i < 6 * quads; ++i) {
          const std::uint32_t g = mesh.indices[gpuCells[c].indexOffset + std::size_t(i)];
          const std::uint32_t r = cpu.indices[cpuCells[c].indexOffset + std::size_t(i)];
          ASSERT_EQ(gpuVertexCell.at(g), cpuVertexCell.at(r)) << "cell " << c << " index " << i;
        }
        comparedQuads += std::size_t(quads);
      }
    }
    EXPECT_GT(comparedQuads, 500u);
  }
};

TEST_F(StackQuadPipelineTest, EachNodeEqualsTheCpuReferenceWithGaussSmoothing) {
  QuadParams params;
  params.nodeCells = 17;
  compareNodes(terrain(), params);
}

TEST_F(StackQuadPipelineTest, EachNodeEqualsTheCpuReferenceWithAWideBoxFilter) {
  QuadParams params;
  params.nodeCells = 9;
  params.filter = SmoothingFilter::Box;
  params.filterRadius = 2;
  compareNodes(terrain(), params);
}

TEST_F(StackQuadPipelineTest, AWholeTerrainInBatchesIsTheCpuReferencesClosedSurface) {
  const QuantisedStacks stacks = terrain();
  QuadParams params;
  params.nodeCells = 9;
  const std::vector<NodeKey> nodes = nodesWithSurface(stacks, params);
  const StackMesh cpu = quadrangulateNodes(stacks, params, nodes);
  Result<StackQuadPipelineGpu> gpu = StackQuadPipelineGpu::create(stacks, params, 16);
  ASSERT_TRUE(gpu) << gpu.error().message;
  ASSERT_TRUE(gpu->run(nodes));  // starts with room for 1024 vertices: grows and reruns
  EXPECT_EQ(gpu->vertexCount(), cpu.vertices.size());
  EXPECT_EQ(gpu->indexCount(), cpu.indices.size());
  const StackMeshCheck cpuCheck = checkStackMesh(cpu);
  const StackMeshCheck gpuCheck = checkStackMesh(gpu->readMesh());
  EXPECT_TRUE(cpuCheck.watertight());
  EXPECT_TRUE(gpuCheck.watertight()) << gpuCheck.unbalancedEdges << " unbalanced edges";
  EXPECT_EQ(gpuCheck.quads, cpuCheck.quads);
  EXPECT_EQ(gpuCheck.vertices, cpuCheck.vertices);
  EXPECT_EQ(gpuCheck.eulerCharacteristic(), cpuCheck.eulerCharacteristic());
  // The indirect draw command the counters hold.
  QuadCounters counters;
  gpu->counterBuffer().download(0, sizeof counters, &counters);
  EXPECT_EQ(counters.indexCount, cpu.indices.size());
  EXPECT_EQ(counters.instanceCount, 1u);
  // Timed stages give the same mesh, and times for every stage.
  ASSERT_TRUE(gpu->run(nodes, true));
  EXPECT_EQ(gpu->indexCount(), cpu.indices.size());
  EXPECT_GT(gpu->stageTimes().density, 0.0);
  EXPECT_GT(gpu->stageTimes().faces, 0.0);
}

TEST_F(StackQuadPipelineTest, RejectsNodesOutsideTheTerrainAndBadParameters) {
  const QuantisedStacks stacks = terrain();
  QuadParams params;
  Result<StackQuadPipelineGpu> gpu = StackQuadPipelineGpu::create(stacks, params);
  ASSERT_TRUE(gpu);
  const NodeKey outside{999, 0, 0};
  EXPECT_FALSE(gpu->run(std::span(&outside, 1)));
  params.filterRadius = -1;
  EXPECT_FALSE(StackQuadPipelineGpu::create(stacks, params));
}

}  // namespace
}  // namespace tellus
