#pragma once
// The quadrangulation pipeline of seed 003 on the GPU: the compute shaders of shaders/stacks/
// running the stages of the CPU reference (stacks/quadrangulation.hpp) on batches of nodes,
// all nodes appending to one vertex buffer and one index buffer through global atomic counters
// whose first words are a DrawElementsIndirectCommand: the mesh is drawn with
// glDrawElementsIndirect and no count is read back to draw it. Needs a current GL 4.5 context.
//
// Buffers grow when a run needs more than they hold: the kernels never write past the
// capacity but the counters still count, so run() reads the counts back after every batch
// (the seed's read-back) and, when they overflowed, grows the buffers (keeping what the
// earlier batches wrote) and redoes that batch.
//
// The octree renderer (`--algo stacks`) runs it over every level of the MipMap at once and with
// stitching instead (lod/stacks/stitched_quadrangulation.hpp is the CPU reference), and reads
// nothing back: makeBatch() runs every stage, with counters per node, and a placement pass
// between allocation and attributes that puts the nodes one after another into staging
// buffers, recording where each went (StagingBuffers). The caller reads those records a frame
// or more later, behind a fence, and copies the meshes into its pool (StackMeshStaging).
#include <array>
#include <cstdint>
#include <functional>
#include <span>
#include <vector>

#include "tellus/core/result.hpp"
#include "tellus/gl/buffer.hpp"
#include "tellus/gl/program.hpp"
#include "tellus/lod/stacks/stack_levels.hpp"
#include "tellus/formats/stacks/quadrangulation.hpp"

namespace tellus {

class StackQuadPipelineGpu {
 public:
  // One node of a batch (octree mode).
  struct NodeJob {
    std::array<int, 3> origin{};       // first sample, in its level's samples
    int level = 0;
    std::array<int, 3> parentFirst{};  // StitchGeometry::parentFirst
    std::uint32_t stitchMask = 0;      // 0: not stitched
  };
  // Where makeBatch() writes (octree mode). placements holds a StagingCursor, then a
  // NodePlacement per node of the staging (shaders/stacks/place.comp).
  struct StagingBuffers {
    const gl::Buffer* vertices = nullptr;  // StackVertex
    std::uint32_t vertexCapacity = 0;
    const gl::Buffer* indices = nullptr;   // uint32, a node's counting from its first vertex
    std::uint32_t indexCapacity = 0;
    const gl::Buffer* morphTargets = nullptr;  // a MorphTarget per vertex, or null: none written
    const gl::Buffer* placements = nullptr;
  };
  struct StagingCursor {
    std::uint32_t vertices = 0, indices = 0;  // placed so far (the next node's firsts)
    std::uint32_t wantedVertices = 0, wantedIndices = 0;  // asked for, placed or not
  };
  struct NodePlacement {
    static constexpr std::uint32_t kNotPlaced = 0xffffffffu;
    std::uint32_t firstVertex = kNotPlaced, vertexCount = 0, firstIndex = 0, indexCount = 0;
    bool placed() const { return firstVertex != kNotPlaced; }
  };
  static_assert(sizeof(StagingCursor) == 16 && sizeof(NodePlacement) == 16);

  // Uploads the stacks (offsets and layers) once. batchNodes: nodes per dispatch (scratch
  // volumes are allocated for that many).
  static Result<StackQuadPipelineGpu> create(const QuantisedStacks& stacks,
                                             const QuadParams& params, int batchNodes = 64);
  // Every level of `levels` (at most 16), for the octree mode.
  static Result<StackQuadPipelineGpu> create(const StackLevels& levels, int batchNodes);

  // Octree mode: the stacks of `levels` again (after an edit), same levels and parameters.
  // With `changed` (one region per level, terrain rows; StackLevels::rebuild's), only those
  // columns are sent: their layers appended to the GPU copy's spare room and their ranges
  // pointed there (the old layers stay unused); when the room runs out, everything is sent
  // again, compacted.
  Status reloadStacks(const StackLevels& levels, const std::vector<StackRegion>& changed = {});

  // Octree mode: the meshes of `jobs` (1 to batchNodes()) into `staging`, placed after what
  // the cursor there says, their placements at 1 + firstPlacement + job (a node's indices
  // count from its first vertex: draw it with that as the base vertex). With morphTargets,
  // each vertex's geomorph target (MorphTarget, two vec4) too, at the vertex's index there.
  // Nothing is read back; the writes are visible to buffer copies and reads after it returns.
  // Errors: a bad batch size, placements past the buffer.
  Status makeBatch(std::span<const NodeJob> jobs, const StagingBuffers& staging,
                   std::uint32_t firstPlacement);
  // makeBatch() bakes the seam blend (lod/stacks/seam_blend.hpp) into stitched nodes' vertices
  // over this many cells (at most seamBandLimit(); 0, the default: none), as
  // quadrangulateStitchedNode's seamBandCells.
  void setSeamBandCells(int cells) { seamBandCells_ = cells; }

  // Quadrangulates `nodes` (keys of NodeGrid::of(stacks, params)) into the output buffers,
  // replacing what they held. With timeStages, every stage of every batch ends in glFinish and
  // stageTimes() gives the sums of their wall times (costs the pipelining between stages).
  // onBatch, when set, is called after each batch's counters are read back with the number of
  // nodes done so far (for progress over a whole terrain, which takes minutes on llvmpipe).
  Status run(std::span<const NodeKey> nodes, bool timeStages = false,
             const std::function<void(std::size_t nodesDone)>& onBatch = {});

  // The counts of the last run (read back at its end).
  std::uint32_t vertexCount() const { return counts_.vertexCount; }
  std::uint32_t indexCount() const { return counts_.indexCount; }
  const QuadStageTimes& stageTimes() const { return stageTimes_; }

  // The outputs: vertices (StackVertex, std430), indices (uint32 triangles) and the counters
  // (QuadCounters: bind as GL_DRAW_INDIRECT_BUFFER, offset 0).
  const gl::Buffer& vertexBuffer() const { return vertices_; }
  const gl::Buffer& indexBuffer() const { return indices_; }
  const gl::Buffer& counterBuffer() const { return counters_; }

  // Read-backs for tests and tools (they wait for the GPU): the mesh of the last run, and the
  // lookup table of the last batch's node `slot` (n^3 CellEntry).
  StackMesh readMesh() const;
  std::vector<CellEntry> readCells(int slot) const;

  const QuadParams& params() const { return params_; }
  int batchNodes() const { return batchNodes_; }

 private:
  static Result<StackQuadPipelineGpu> createFor(const std::vector<const QuantisedStacks*>& levels,
                                                const QuadParams& params, int batchNodes);
  void uploadStacks(const std::vector<const QuantisedStacks*>& levels);
  // reloadStacks()'s partial upload; false (nothing sent) when the spare room is too small.
  bool patchStacks(const StackLevels& levels, const std::vector<StackRegion>& changed);
  void uploadJobs(std::span<const NodeJob> jobs, bool sharedCounters);
  void countStages(std::size_t count, bool timeStages);
  void writeStages(std::size_t count, bool timeStages);
  void timeStage(int index, bool timeStages, const std::function<void()>& body);
  // Grows the output buffers to at least these counts, keeping their first keep* elements.
  void ensureCapacity(std::uint32_t vertices, std::uint32_t indices, std::uint32_t keepVertices,
                      std::uint32_t keepIndices);

  QuantisedStacks stacksShape_;  // sizes and spacings only (the layers live on the GPU)
  QuadParams params_;
  NodeGrid grid_;
  int batchNodes_ = 0;
  int seamBandCells_ = 0;
  bool octree_ = false;
  gl::Program density_, smooth_, stitch_, classify_, allocate_, place_, attributes_, faces_;
  // The GPU copy of the stacks: per column of every level its [first, end) layers (absolute
  // indices into layers_), and the layers, with spare room after the first layerCursor_ of
  // layerCapacity_ for edited columns.
  gl::Buffer ranges_, layers_, nodes_, volumeA_, volumeB_, coarseA_, coarseB_, cells_;
  std::size_t layerCursor_ = 0, layerCapacity_ = 0;
  std::vector<glm::ivec4> levelLayout_;  // per level: first column, 0, width, height
  gl::Buffer counters_, vertices_, indices_;
  std::uint32_t vertexCapacity_ = 0, indexCapacity_ = 0;
  QuadCounters counts_;
  QuadStageTimes stageTimes_;
};

}  // namespace tellus
