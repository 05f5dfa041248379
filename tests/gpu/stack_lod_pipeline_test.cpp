// The quadrangulation pipeline's octree mode on the GPU (StackQuadPipelineGpu::makeBatch): every
// level at once, stitched nodes, meshes placed by the GPU one after another in staging buffers,
// against the CPU reference (lod/stacks/stitched_quadrangulation.hpp) cell for cell, the whole
// selection closed, and a staging too small turning nodes away without writing past its end.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <bit>
#include <span>

#include "support/gl_test.hpp"
#include "support/stack_fixtures.hpp"
#include "tellus/gl/program.hpp"
#include "tellus/gl/transform_feedback.hpp"
#include "tellus/gl/vertex_array.hpp"
#include "tellus/lod/stacks/seam_blend.hpp"
#include "tellus/lod/stacks/stitched_quadrangulation.hpp"
#include "tellus/render/output/offscreen_target.hpp"
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
  // Staging buffers for `nodes` nodes of at most these many vertices and indices.
  struct Staging {
    gl::Buffer vertices, indices, targets, placements;
    StackQuadPipelineGpu::StagingBuffers buffers;
    Staging(std::uint32_t vertexCount, std::uint32_t indexCount, std::size_t nodes)
        : vertices(std::size_t(vertexCount) * sizeof(StackVertex), nullptr, GL_DYNAMIC_STORAGE_BIT),
          indices(std::size_t(indexCount) * 4, nullptr),
          targets(std::size_t(vertexCount) * sizeof(MorphTarget), nullptr),
          placements((1 + nodes) * 16, nullptr, GL_DYNAMIC_STORAGE_BIT) {
      const StackQuadPipelineGpu::StagingCursor empty;
      placements.upload(0, sizeof empty, &empty);
      buffers = {&vertices, vertexCount, &indices, indexCount, &targets, &placements};
    }
    std::vector<StackQuadPipelineGpu::NodePlacement> read(std::size_t nodes,
                                                          StackQuadPipelineGpu::StagingCursor& cursor) const {
      std::vector<StackQuadPipelineGpu::NodePlacement> out(1 + nodes);
      placements.download(0, out.size() * 16, out.data());
      cursor = std::bit_cast<StackQuadPipelineGpu::StagingCursor>(out[0]);
      out.erase(out.begin());
      return out;
    }
  };
  // The selection from above the hills, looking down (several levels, stitched nodes).
  static StackSelection selectionFrom(const StackOctree& octree) {
    SelectionView view;
    view.camera = {40.0, 60.0, 90.0};
    view.fovYDeg = 60.0;
    view.viewportHeightPx = 720;
    view.tauPx = 60.0;
    return selectStackNodes(octree, view);
  }
  static std::vector<StackQuadPipelineGpu::NodeJob> jobsOf(const StackOctree& octree,
                                                           std::span<const SelectedNode> nodes) {
    std::vector<StackQuadPipelineGpu::NodeJob> jobs;
    for (const SelectedNode& node : nodes) {
      const StitchGeometry geometry = StitchGeometry::of(octree, node.key, node.stitchMask);
      jobs.push_back({octree.origin(node.key), node.key.level, geometry.parentFirst, node.stitchMask});
    }
    return jobs;
  }
};

TEST_F(StackLodPipelineTest, StitchedNodesMatchTheCpuReferenceAndCloseTheSurface) {
  const StackLevels stackLevels = levels();
  const StackOctree octree(stackLevels);
  const StackSelection selection = selectionFrom(octree);
  ASSERT_GT(selection.nodes.size(), 20u);
  Result<StackQuadPipelineGpu> gpu = StackQuadPipelineGpu::create(stackLevels, 16);
  ASSERT_TRUE(gpu) << gpu.error().message;
  const int n = stackLevels.params().nodeCells;
  const std::size_t cellCount = std::size_t(n) * n * n;
  // The seam blend baked in at its widest band (3 cells for n = 9), on the CPU too.
  const int band = seamBandLimit(n);
  gpu->setSeamBandCells(band);

  // Every batch into one staging, with room for all: the cursor carries on across batches.
  const std::size_t nodeCount = selection.nodes.size();
  Staging staging(std::uint32_t(nodeCount * cellCount), std::uint32_t(18 * nodeCount * cellCount), nodeCount);
  std::vector<std::vector<CellEntry>> gpuCellsOf(nodeCount);
  for (std::size_t first = 0; first < nodeCount; first += 16) {
    const std::size_t size = std::min<std::size_t>(16, nodeCount - first);
    const std::span<const SelectedNode> batch(selection.nodes.data() + first, size);
    ASSERT_TRUE(gpu->makeBatch(jobsOf(octree, batch), staging.buffers, std::uint32_t(first)));
    for (std::size_t i = 0; i < size; ++i) gpuCellsOf[first + i] = gpu->readCells(int(i));
  }
  StackQuadPipelineGpu::StagingCursor cursor;
  const std::vector<StackQuadPipelineGpu::NodePlacement> placements = staging.read(nodeCount, cursor);
  EXPECT_EQ(cursor.vertices, cursor.wantedVertices);
  EXPECT_EQ(cursor.indices, cursor.wantedIndices);
  std::vector<StackVertex> gpuVertices(cursor.vertices);
  std::vector<std::uint32_t> gpuIndices(cursor.indices);
  std::vector<MorphTarget> gpuTargets(cursor.vertices);
  staging.vertices.download(0, gpuVertices.size() * sizeof(StackVertex), gpuVertices.data());
  staging.indices.download(0, gpuIndices.size() * 4, gpuIndices.data());
  staging.targets.download(0, gpuTargets.size() * sizeof(MorphTarget), gpuTargets.data());

  StackMesh all;  // the GPU's meshes, rebased into one mesh
  std::size_t stitched = 0, comparedQuads = 0, morphing = 0;
  std::uint32_t nextVertex = 0, nextIndex = 0;  // placed one after another, in order
  for (std::size_t i = 0; i < nodeCount; ++i) {
    const SelectedNode& node = selection.nodes[i];
    const StackQuadPipelineGpu::NodePlacement& at = placements[i];
    ASSERT_TRUE(at.placed()) << "node " << i;
    ASSERT_EQ(at.firstVertex, nextVertex);
    ASSERT_EQ(at.firstIndex, nextIndex);
    nextVertex += at.vertexCount;
    nextIndex += at.indexCount;
    if (node.stitchMask != 0u) ++stitched;
    StackMesh cpu;
    std::vector<CellEntry> cpuCells;
    StitchStats stats;
    std::vector<MorphTarget> cpuTargets;
    quadrangulateStitchedNode(octree, node.key, node.stitchMask, cpu, &cpuCells, &stats, &cpuTargets, band);
    ASSERT_EQ(cpuTargets.size(), cpu.vertices.size());
    ASSERT_EQ(stats.faults, 0u);
    ASSERT_EQ(at.vertexCount, cpu.vertices.size());
    ASSERT_EQ(at.indexCount, cpu.indices.size());
    const std::vector<CellEntry>& gpuCells = gpuCellsOf[i];
    // The GPU numbers rows in the order its atomics ran: map through the cell tables.
    std::vector<std::uint32_t> toGpu(cpu.vertices.size(), ~0u);
    for (std::size_t c = 0; c < cellCount; ++c) {
      ASSERT_EQ(gpuCells[c].code, cpuCells[c].code) << "cell " << c;
      if (!dc::codeHasVertex(cpuCells[c].code)) continue;
      toGpu[cpuCells[c].vertexIndex] = gpuCells[c].vertexIndex;
      const StackVertex& a = cpu.vertices[cpuCells[c].vertexIndex];
      const StackVertex& b = gpuVertices[at.firstVertex + gpuCells[c].vertexIndex];
      const MorphTarget& ta = cpuTargets[cpuCells[c].vertexIndex];
      const MorphTarget& tb = gpuTargets[at.firstVertex + gpuCells[c].vertexIndex];
      for (int k = 0; k < 3; ++k) {
        ASSERT_NEAR(a.position[std::size_t(k)], b.position[std::size_t(k)], 1e-3f) << "cell " << c;
        ASSERT_NEAR(a.normal[std::size_t(k)], b.normal[std::size_t(k)], 1e-3f) << "cell " << c;
        ASSERT_NEAR(ta[std::size_t(k)], tb[std::size_t(k)], 1e-3f) << "target, cell " << c;
      }
      ASSERT_EQ(ta[3], tb[3]) << "border bits, cell " << c;
      for (std::size_t k = 4; k < 7; ++k) ASSERT_NEAR(ta[k], tb[k], 1e-3f) << "target normal, cell " << c;
      const std::array<float, 4> ma = unpackMaterials(ta[7]), mb = unpackMaterials(tb[7]);
      for (std::size_t m = 0; m < 4; ++m) ASSERT_NEAR(ma[m], mb[m], 1.01f / 255.0f) << "target materials, cell " << c;
      if (ta[0] != a.position[0] || ta[1] != a.position[1] || ta[2] != a.position[2]) ++morphing;
    }
    for (std::size_t c = 0; c < cellCount; ++c) {
      const int quads = std::popcount(dc::codeQuads(cpuCells[c].code));
      for (int q = 0; q < 6 * quads; ++q) {
        const std::uint32_t cpuIndex = cpu.indices[cpuCells[c].indexOffset + std::size_t(q)];
        const std::uint32_t gpuIndex = gpuIndices[at.firstIndex + gpuCells[c].indexOffset + std::size_t(q)];
        ASSERT_EQ(toGpu[cpuIndex], gpuIndex) << "cell " << c << " index " << q;
      }
      comparedQuads += std::size_t(quads);
    }
    // Into the combined mesh.
    const auto base = std::uint32_t(all.vertices.size());
    all.vertices.insert(all.vertices.end(), gpuVertices.begin() + at.firstVertex,
                        gpuVertices.begin() + at.firstVertex + at.vertexCount);
    for (std::uint32_t k = 0; k < at.indexCount; ++k) all.indices.push_back(base + gpuIndices[at.firstIndex + k]);
  }
  EXPECT_GT(stitched, 0u);
  EXPECT_GT(comparedQuads, 1000u);
  EXPECT_GT(morphing, 1000u);  // vertices whose target is not themselves
  const StackMeshCheck check = checkStackMesh(all);
  EXPECT_EQ(check.unbalancedEdges, 0u);
}

TEST_F(StackLodPipelineTest, AFullStagingTurnsNodesAwayAndSaysWhatAllWanted) {
  const StackLevels stackLevels = levels();
  const StackOctree octree(stackLevels);
  const StackSelection selection = selectionFrom(octree);
  ASSERT_GE(selection.nodes.size(), 16u);
  Result<StackQuadPipelineGpu> gpu = StackQuadPipelineGpu::create(stackLevels, 16);
  ASSERT_TRUE(gpu) << gpu.error().message;
  const std::span<const SelectedNode> batch(selection.nodes.data(), 16);
  const std::vector<StackQuadPipelineGpu::NodeJob> jobs = jobsOf(octree, batch);
  // What the 16 nodes need, from a staging large enough.
  const std::size_t cells = 9 * 9 * 9;
  Staging large(std::uint32_t(16 * cells), std::uint32_t(16 * 18 * cells), 16);
  ASSERT_TRUE(gpu->makeBatch(jobs, large.buffers, 0));
  StackQuadPipelineGpu::StagingCursor needed;
  const std::vector<StackQuadPipelineGpu::NodePlacement> all = large.read(16, needed);
  ASSERT_GT(needed.vertices, 100u);
  // Room for about half of the vertices: the nodes that fit are placed in order, the rest not,
  // and nothing is written past the end (a sentinel vertex after the capacity stays).
  const std::uint32_t capacity = needed.vertices / 2;
  Staging small(capacity + 1, needed.indices, 16);
  const StackVertex sentinel{{7.0f, 7.0f, 7.0f, 7.0f}, {}, {}};
  small.vertices.upload(std::size_t(capacity) * sizeof(StackVertex), sizeof sentinel, &sentinel);
  small.buffers.vertexCapacity = capacity;
  ASSERT_TRUE(gpu->makeBatch(jobs, small.buffers, 0));
  StackQuadPipelineGpu::StagingCursor cursor;
  const std::vector<StackQuadPipelineGpu::NodePlacement> some = small.read(16, cursor);
  EXPECT_EQ(cursor.wantedVertices, needed.vertices);
  EXPECT_EQ(cursor.wantedIndices, needed.indices);
  EXPECT_LE(cursor.vertices, capacity);
  std::size_t placed = 0, turnedAway = 0;
  std::uint32_t next = 0;
  for (std::size_t i = 0; i < 16; ++i) {
    EXPECT_EQ(some[i].vertexCount, all[i].vertexCount);
    EXPECT_EQ(some[i].indexCount, all[i].indexCount);
    if (!some[i].placed()) {
      ++turnedAway;
      continue;
    }
    ++placed;
    EXPECT_EQ(some[i].firstVertex, next);
    next += some[i].vertexCount;
  }
  EXPECT_GT(placed, 0u);
  EXPECT_GT(turnedAway, 0u);
  StackVertex after{};
  small.vertices.download(std::size_t(capacity) * sizeof(StackVertex), sizeof after, &after);
  EXPECT_EQ(after.position[0], 7.0f);
  EXPECT_EQ(after.position[3], 7.0f);
}

TEST_F(StackLodPipelineTest, RejectsBadBatches) {
  const StackLevels stackLevels = levels();
  Result<StackQuadPipelineGpu> gpu = StackQuadPipelineGpu::create(stackLevels, 2);
  ASSERT_TRUE(gpu);
  Staging staging(1024, 8192, 2);
  std::vector<StackQuadPipelineGpu::NodeJob> three(3);
  EXPECT_FALSE(gpu->makeBatch(three, staging.buffers, 0));
  EXPECT_FALSE(gpu->makeBatch({}, staging.buffers, 0));
  std::vector<StackQuadPipelineGpu::NodeJob> two(2);
  EXPECT_FALSE(gpu->makeBatch(two, staging.buffers, 1));  // placements past the buffer
}

// The vertex shader that draws `stacks` meshes (stacks.vert with stacks/vertex_morph.glsl: the
// geomorph and its pins), run through transform feedback on the vertices of stitched nodes (the
// seam blend baked in) with their CPU targets, against the CPU reference drawnStackVertex.
TEST_F(StackLodPipelineTest, TheVertexShaderDrawsVerticesWhereTheCpuReferenceDoes) {
  const StackLevels lv = levels();
  const StackOctree octree(lv);
  const int band = seamBandLimit(octree.nodeCells());
  const StackSelection selection = selectionFrom(octree);
  Result<gl::Program> program = gl::Program::fromFiles(
      {{GL_VERTEX_SHADER, "stacks/stacks.vert"}, {GL_FRAGMENT_SHADER, "stacks/stacks.frag"}},
      {"vRelativePosition", "vNormal", "vMaterials"});
  ASSERT_TRUE(program) << program.error().message;
  program->set("uViewProjection", glm::mat4(1.0f));
  program->set("uCameraPosition", glm::vec3(0.0f));
  program->set("uExaggeration", 1.0f);
  program->set("uFinestCellM", 2.0f);
  program->set("uMorph", 1);
  // Rasterisation is discarded, but a draw needs a complete framebuffer.
  Result<OffscreenTarget> target = OffscreenTarget::create(4, 4, 1);
  ASSERT_TRUE(target) << target.error().message;
  target->begin({0, 0, 0});
  struct NodeValue {
    float factor;
    std::uint32_t unlike;
  };
  std::size_t nodes = 0, compared = 0, blended = 0;
  for (const SelectedNode& node : selection.nodes) {
    if (node.stitchMask == 0u || nodes >= 12) continue;
    ++nodes;
    StackMesh mesh;
    std::vector<MorphTarget> targets;
    quadrangulateStitchedNode(octree, node.key, node.stitchMask, mesh, nullptr, nullptr, &targets, band);
    if (mesh.vertices.empty()) continue;
    // Half the nodes slide (factor 0.3) with two unlike neighbours (-x, and +y +z).
    const bool slides = nodes % 2 == 0;
    const NodeValue value{slides ? 0.3f : 1.0f,
                          slides ? (1u << neighbourBit(-1, 0, 0)) | (1u << neighbourBit(0, 1, 1)) : 0u};
    gl::Buffer vertices(mesh.vertices.size() * sizeof(StackVertex), mesh.vertices.data());
    gl::Buffer morph(targets.size() * sizeof(MorphTarget), targets.data());
    gl::Buffer instance(sizeof value, &value);
    constexpr std::size_t kCaptured = 10;  // position, normal, materials
    gl::Buffer captured(mesh.vertices.size() * kCaptured * sizeof(float), nullptr);
    gl::VertexArray array = gl::VertexArray::create();
    array.setInstanceBuffer(0, instance, sizeof(NodeValue));
    array.setFloatAttribute(0, 0, 1, offsetof(NodeValue, factor));
    array.setUintAttribute(1, 0, 1, offsetof(NodeValue, unlike));
    gl::TransformFeedback feedback = gl::TransformFeedback::create();
    feedback.captureInto(captured);
    program->use();
    array.bind();
    vertices.bindBase(GL_SHADER_STORAGE_BUFFER, 0);
    morph.bindBase(GL_SHADER_STORAGE_BUFFER, 1);
    glEnable(GL_RASTERIZER_DISCARD);
    feedback.bind();
    glBeginTransformFeedback(GL_POINTS);
    glDrawArraysInstanced(GL_POINTS, 0, GLsizei(mesh.vertices.size()), 1);
    glEndTransformFeedback();
    glBindTransformFeedback(GL_TRANSFORM_FEEDBACK, 0);
    glDisable(GL_RASTERIZER_DISCARD);
    std::vector<float> gpu(mesh.vertices.size() * kCaptured);
    captured.download(0, gpu.size() * sizeof(float), gpu.data());
    for (std::size_t v = 0; v < mesh.vertices.size(); ++v) {
      const StackVertex cpu =
          drawnStackVertex(mesh.vertices[v], targets[v], value.factor, value.unlike);
      if (cpu.position != mesh.vertices[v].position) ++blended;
      const float* out = &gpu[v * kCaptured];
      for (std::size_t a = 0; a < 3; ++a) {
        ASSERT_NEAR(out[a], cpu.position[a], 1e-3f * (1.0f + std::fabs(cpu.position[a])))
            << "vertex " << v << " of node level " << node.key.level << " axis " << a;
        ASSERT_NEAR(out[3 + a], cpu.normal[a], 1e-4f) << "normal, vertex " << v;
      }
      for (std::size_t m = 0; m < 4; ++m) ASSERT_NEAR(out[6 + m], cpu.materials[m], 1e-4f) << "materials, vertex " << v;
      ++compared;
    }
  }
  EXPECT_GE(nodes, 6u);
  EXPECT_GT(compared, 500u);
  EXPECT_GT(blended, 100u);
  std::printf("%zu vertices of %zu stitched nodes compared, %zu moved\n", compared, nodes, blended);
}

}  // namespace
}  // namespace tellus
