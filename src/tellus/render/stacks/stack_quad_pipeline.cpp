#include "tellus/render/stacks/stack_quad_pipeline.hpp"

#include <algorithm>
#include <array>
#include <chrono>

#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include "tellus/core/stopwatch.hpp"
#include "tellus/gl/gpu_wait.hpp"
#include "tellus/lod/stacks/seam_blend.hpp"
#include "tellus/lod/stacks/stitched_quadrangulation.hpp"

namespace tellus {
namespace {

constexpr GLuint kRanges = 0, kLayers = 1, kNodes = 2, kVolumeIn = 3, kVolumeOut = 4,
                 kCells = 5, kCounters = 6, kVertices = 7, kIndices = 8, kCoarseSmoothed = 9,
                 kMorphTargets = 10, kPlacements = 11;
constexpr int kMaxLevels = 16;

// A batch node as the shaders read it (NodeInfo in quad_common.glsl, std430).
struct NodeInfo {
  std::array<int, 4> origin;     // xyz, level
  std::array<int, 4> stitch;     // parent's first cell xyz, mask
  std::array<std::uint32_t, 4> dest;  // first vertex, first index, counters, -
};
static_assert(sizeof(NodeInfo) == 48);

using gl::workGroups;

std::size_t cube(int side) { return std::size_t(side) * std::size_t(side) * std::size_t(side); }

}  // namespace

Result<StackQuadPipelineGpu> StackQuadPipelineGpu::create(const QuantisedStacks& stacks,
                                                          const QuadParams& params,
                                                          int batchNodes) {
  Result<StackQuadPipelineGpu> p = createFor({&stacks}, params, batchNodes);
  if (!p) return p.error();
  p->grid_ = NodeGrid::of(stacks, params);
  return p;
}

Result<StackQuadPipelineGpu> StackQuadPipelineGpu::create(const StackLevels& levels,
                                                          int batchNodes) {
  std::vector<const QuantisedStacks*> all;
  for (int k = 0; k < std::min(levels.count(), kMaxLevels); ++k) all.push_back(&levels.level(k).stacks);
  Result<StackQuadPipelineGpu> p = createFor(all, levels.params(), batchNodes);
  if (!p) return p.error();
  p->octree_ = true;
  // The nodes' volumes of the next coarser level (stitching, geomorph targets).
  const QuadParams coarse = coarseVolumeParams(levels.params());
  p->coarseA_ = gl::Buffer(std::size_t(batchNodes) * cube(coarse.rawSide()) * 16, nullptr);
  p->coarseB_ = gl::Buffer(std::size_t(batchNodes) * cube(coarse.rawSide()) * 16, nullptr);
  for (gl::Program* program : {&p->density_, &p->smooth_, &p->stitch_, &p->classify_,
                               &p->allocate_, &p->attributes_, &p->faces_}) {
    program->set("uCoarseRawSide", coarse.rawSide());
    program->set("uCoarseSmoothSide", coarse.smoothSide());
  }
  return p;
}

Result<StackQuadPipelineGpu> StackQuadPipelineGpu::createFor(
    const std::vector<const QuantisedStacks*>& levels, const QuadParams& params, int batchNodes) {
  if (Status ok = params.check(); !ok) return ok.error();
  if (batchNodes < 1 || batchNodes > 4096) {
    return makeError("nodes per batch must be 1 to 4096 (got {})", batchNodes);
  }
  std::size_t layerCount = 0, offsetCount = 0;
  for (const QuantisedStacks* s : levels) {
    layerCount += s->layers.size();
    offsetCount += s->offsets.size();
  }
  if (layerCount >= (std::size_t(1) << 31) / sizeof(QuantisedLayer)) {
    return makeError("{} layers do not fit one GPU buffer", layerCount);
  }
  StackQuadPipelineGpu p;
  p.params_ = params;
  p.batchNodes_ = batchNodes;
  const QuantisedStacks& finest = *levels.front();
  p.stacksShape_.width = finest.width;
  p.stacksShape_.height = finest.height;
  p.stacksShape_.cellsZ = finest.cellsZ;
  p.stacksShape_.spacingM = finest.spacingM;
  p.stacksShape_.cellM = finest.cellM;
  if (Status built = gl::buildComputePrograms({{&p.density_, "stacks/density.comp"},
                                                {&p.smooth_, "stacks/smooth.comp"},
                                                {&p.stitch_, "stacks/stitch.comp"},
                                                {&p.classify_, "stacks/classify.comp"},
                                                {&p.allocate_, "stacks/allocate.comp"},
                                                {&p.place_, "stacks/place.comp"},
                                                {&p.attributes_, "stacks/attributes.comp"},
                                                {&p.faces_, "stacks/faces.comp"}});
      !built) {
    return built.error();
  }
  p.uploadStacks(levels);
  p.nodes_ = gl::Buffer(std::size_t(batchNodes) * sizeof(NodeInfo), nullptr, GL_DYNAMIC_STORAGE_BIT);
  p.volumeA_ = gl::Buffer(std::size_t(batchNodes) * cube(params.rawSide()) * 16, nullptr);
  p.volumeB_ = gl::Buffer(std::size_t(batchNodes) * cube(params.rawSide()) * 16, nullptr);
  p.coarseA_ = gl::Buffer(16, nullptr);  // bound but unread without stitching
  p.coarseB_ = gl::Buffer(16, nullptr);
  p.cells_ = gl::Buffer(std::size_t(batchNodes) * cube(params.nodeCells) * sizeof(CellEntry), nullptr,
                        GL_DYNAMIC_STORAGE_BIT);
  p.counters_ = gl::Buffer(std::size_t(batchNodes) * sizeof(QuadCounters), nullptr,
                           GL_DYNAMIC_STORAGE_BIT);

  const std::vector<std::uint32_t> taps = params.filterTaps();
  std::array<int, 9> tapValues{};
  for (std::size_t t = 0; t < taps.size(); ++t) tapValues[t] = int(taps[t]);
  for (gl::Program* program : {&p.density_, &p.smooth_, &p.stitch_, &p.classify_, &p.allocate_,
                               &p.attributes_, &p.faces_}) {
    program->set("uNodeCells", params.nodeCells);
    program->set("uFilterRadius", params.filterRadius);
    program->set("uRawSide", params.rawSide());
    program->set("uSmoothSide", params.smoothSide());
  }
  p.smooth_.setArray("uTaps", tapValues.data(), int(tapValues.size()));
  p.classify_.set("uIsoTwice", int(params.isoTwice()));
  p.attributes_.set("uIsoTwice", int(params.isoTwice()));
  p.ensureCapacity(1024, 6 * 1024, 0, 0);
  return p;
}

void StackQuadPipelineGpu::uploadStacks(const std::vector<const QuantisedStacks*>& levels) {
  // Every level's columns as [first, end) ranges into one array of layers; the shaders find a
  // level's columns by its layout.
  std::vector<std::uint32_t> ranges;
  std::vector<QuantisedLayer> layers;
  std::array<glm::ivec4, kMaxLevels> layout{};
  std::array<glm::vec4, kMaxLevels> geometry{};
  for (std::size_t k = 0; k < levels.size(); ++k) {
    const QuantisedStacks& s = *levels[k];
    layout[k] = {int(ranges.size() / 2), 0, s.width, s.height};
    geometry[k] = {float(s.spacingM), float(s.cellM), float(s.baseM), 0.0f};
    const auto first = std::uint32_t(layers.size());
    for (std::size_t c = 0; c + 1 < s.offsets.size(); ++c) {
      ranges.push_back(first + s.offsets[c]);
      ranges.push_back(first + s.offsets[c + 1]);
    }
    layers.insert(layers.end(), s.layers.begin(), s.layers.end());
  }
  levelLayout_.assign(layout.begin(), layout.begin() + std::ptrdiff_t(levels.size()));
  if (ranges.empty()) ranges.push_back(0);  // an empty terrain still needs buffers to bind
  // Spare room for edits: an eighth more (at least a million layers), within one buffer's
  // 2 GiB (reloadStacks checked that the layers themselves fit).
  const std::size_t limit = ((std::size_t(1) << 31) - 1) / sizeof(QuantisedLayer);
  layerCursor_ = layers.size();
  layerCapacity_ = std::min(limit, std::max<std::size_t>(layers.size() + layers.size() / 8,
                                                         layers.size() + (std::size_t(1) << 20)));
  layerCapacity_ = std::max<std::size_t>(layerCapacity_, 1);
  ranges_ = gl::Buffer(ranges.size() * sizeof(std::uint32_t), ranges.data(), GL_DYNAMIC_STORAGE_BIT);
  layers_ = gl::Buffer(layerCapacity_ * sizeof(QuantisedLayer), nullptr, GL_DYNAMIC_STORAGE_BIT);
  if (!layers.empty()) layers_.upload(0, layers.size() * sizeof(QuantisedLayer), layers.data());
  for (gl::Program* program : {&density_, &smooth_, &stitch_, &classify_, &allocate_,
                               &attributes_, &faces_}) {
    program->setArray("uLevelLayout", layout.data(), kMaxLevels);
    program->setArray("uLevelGeometry", geometry.data(), kMaxLevels);
  }
}

bool StackQuadPipelineGpu::patchStacks(const StackLevels& levels,
                                       const std::vector<StackRegion>& changed) {
  std::vector<QuantisedLayer> appended;
  struct RangeRow {
    std::size_t firstColumn;  // in the ranges buffer (all levels)
    std::vector<std::uint32_t> ranges;
  };
  std::vector<RangeRow> rows;
  for (std::size_t k = 0; k < changed.size(); ++k) {
    if (changed[k].empty()) continue;
    if (k >= levelLayout_.size()) return false;
    const QuantisedStacks& s = levels.level(int(k)).stacks;
    const glm::ivec4& layout = levelLayout_[k];
    if (s.width != layout.z || s.height != layout.w) return false;
    const StackRegion& r = changed[k];
    // Terrain rows to sample rows (y north), as the columns are stored.
    for (int y = s.height - 1 - r.y1; y <= s.height - 1 - r.y0; ++y) {
      RangeRow row{std::size_t(layout.x) + std::size_t(r.x0) + std::size_t(s.width) * std::size_t(y), {}};
      for (int x = r.x0; x <= r.x1; ++x) {
        const std::span<const QuantisedLayer> column = s.column(x, y);
        const std::size_t first = layerCursor_ + appended.size();
        row.ranges.push_back(std::uint32_t(first));
        row.ranges.push_back(std::uint32_t(first + column.size()));
        appended.insert(appended.end(), column.begin(), column.end());
      }
      rows.push_back(std::move(row));
    }
  }
  if (layerCursor_ + appended.size() > layerCapacity_) return false;
  if (!appended.empty()) {
    layers_.upload(layerCursor_ * sizeof(QuantisedLayer), appended.size() * sizeof(QuantisedLayer),
                   appended.data());
  }
  layerCursor_ += appended.size();
  for (const RangeRow& row : rows) {
    ranges_.upload(2 * row.firstColumn * sizeof(std::uint32_t),
                   row.ranges.size() * sizeof(std::uint32_t), row.ranges.data());
  }
  return true;
}

Status StackQuadPipelineGpu::reloadStacks(const StackLevels& levels,
                                          const std::vector<StackRegion>& changed) {
  if (!octree_) return makeError("reloadStacks needs a pipeline over stack levels");
  if (!changed.empty() && patchStacks(levels, changed)) return {};
  std::vector<const QuantisedStacks*> all;
  for (int k = 0; k < std::min(levels.count(), kMaxLevels); ++k) all.push_back(&levels.level(k).stacks);
  std::size_t layerCount = 0;
  for (const QuantisedStacks* s : all) layerCount += s->layers.size();
  if (layerCount >= (std::size_t(1) << 31) / sizeof(QuantisedLayer)) {
    return makeError("{} layers do not fit one GPU buffer", layerCount);
  }
  uploadStacks(all);
  return {};
}

void StackQuadPipelineGpu::ensureCapacity(std::uint32_t vertices, std::uint32_t indices,
                                          std::uint32_t keepVertices, std::uint32_t keepIndices) {
  // A larger buffer, holding what the old one had written so far.
  const auto grow = [](gl::Buffer& buffer, std::size_t bytes, std::size_t keepBytes) {
    gl::Buffer larger(bytes, nullptr);
    if (keepBytes > 0) glCopyNamedBufferSubData(buffer.id(), larger.id(), 0, 0, GLsizeiptr(keepBytes));
    buffer = std::move(larger);
  };
  if (vertices > vertexCapacity_) {
    grow(vertices_, std::size_t(vertices) * sizeof(StackVertex), std::size_t(keepVertices) * sizeof(StackVertex));
    vertexCapacity_ = vertices;
  }
  if (indices > indexCapacity_) {
    grow(indices_, std::size_t(indices) * sizeof(std::uint32_t), std::size_t(keepIndices) * sizeof(std::uint32_t));
    indexCapacity_ = indices;
  }
}

void StackQuadPipelineGpu::uploadJobs(std::span<const NodeJob> jobs, bool sharedCounters) {
  std::vector<NodeInfo> info;
  for (std::size_t i = 0; i < jobs.size(); ++i) {
    const NodeJob& job = jobs[i];
    info.push_back({{job.origin[0], job.origin[1], job.origin[2], job.level},
                    {job.parentFirst[0], job.parentFirst[1], job.parentFirst[2], int(job.stitchMask)},
                    {0u, 0u, sharedCounters ? 0u : std::uint32_t(i), 0u}});
  }
  nodes_.upload(0, info.size() * sizeof(NodeInfo), info.data());
  for (gl::Program* program : {&density_, &smooth_, &stitch_, &classify_, &allocate_, &place_,
                               &attributes_, &faces_}) {
    program->set("uBatchCount", int(jobs.size()));
  }
  ranges_.bindBase(GL_SHADER_STORAGE_BUFFER, kRanges);
  layers_.bindBase(GL_SHADER_STORAGE_BUFFER, kLayers);
  nodes_.bindBase(GL_SHADER_STORAGE_BUFFER, kNodes);
  cells_.bindBase(GL_SHADER_STORAGE_BUFFER, kCells);
  counters_.bindBase(GL_SHADER_STORAGE_BUFFER, kCounters);
}

void StackQuadPipelineGpu::timeStage(int index, bool timeStages, const std::function<void()>& body) {
  // Timed stages end in glFinish and are timed on the CPU clock: software rasterisers (Mesa's
  // llvmpipe) report no time for compute dispatches in GL_TIME_ELAPSED queries.
  const Stopwatch start;
  body();
  glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
  if (!timeStages) return;
  gl::finish();
  const double ms =
      start.elapsedMs();
  double* slots[] = {&stageTimes_.density, &stageTimes_.smooth,     &stageTimes_.classify,
                     &stageTimes_.allocate, &stageTimes_.attributes, &stageTimes_.faces};
  *slots[index] += ms;
}

void StackQuadPipelineGpu::countStages(std::size_t count, bool timeStages) {
  const int n = params_.nodeCells;
  const auto batch = GLuint(count);
  // Density then smoothing of one volume a node: A -> B (x), B -> A (y), A -> B (z).
  const auto densityAndSmooth = [&](int rawSide, const gl::Buffer& a, const gl::Buffer& b,
                                    bool coarsePass) {
    a.bindBase(GL_SHADER_STORAGE_BUFFER, kVolumeIn);
    density_.use();
    density_.set("uVolumeSide", rawSide);
    density_.set("uCoarsePass", coarsePass ? 1 : 0);
    glDispatchCompute(workGroups(std::size_t(rawSide), 8), workGroups(std::size_t(rawSide), 8), batch);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    smooth_.use();
    smooth_.set("uVolumeSide", rawSide);
    glm::ivec3 size(rawSide, rawSide, rawSide);
    for (int axis = 0; axis < 3; ++axis) {
      const gl::Buffer& in = axis == 1 ? b : a;
      const gl::Buffer& out = axis == 1 ? a : b;
      in.bindBase(GL_SHADER_STORAGE_BUFFER, kVolumeIn);
      out.bindBase(GL_SHADER_STORAGE_BUFFER, kVolumeOut);
      smooth_.set("uAxis", axis);
      smooth_.set("uInSize", size);
      size[axis] -= 2 * params_.filterRadius;
      glDispatchCompute(workGroups(std::size_t(size.x) * size.y * size.z, 64), batch, 1);
      if (axis < 2) glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    }
  };
  timeStage(0, timeStages, [&] {
    if (octree_) densityAndSmooth(coarseVolumeParams(params_).rawSide(), coarseA_, coarseB_, true);
  });
  timeStage(1, timeStages, [&] {
    densityAndSmooth(params_.rawSide(), volumeA_, volumeB_, false);
    volumeB_.bindBase(GL_SHADER_STORAGE_BUFFER, kVolumeOut);  // the smoothed density
    coarseB_.bindBase(GL_SHADER_STORAGE_BUFFER, kCoarseSmoothed);
    if (octree_) {
      glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
      stitch_.use();
      glDispatchCompute(workGroups(cube(params_.smoothSide()), 64), batch, 1);
    }
  });
  timeStage(2, timeStages, [&] {
    classify_.use();
    glDispatchCompute(workGroups(cube(n), 64), batch, 1);
  });
  timeStage(3, timeStages, [&] {
    allocate_.use();
    glDispatchCompute(workGroups(std::size_t(n) * n, 64), batch, 1);
  });
}

void StackQuadPipelineGpu::writeStages(std::size_t count, bool timeStages) {
  const auto batch = GLuint(count);
  const std::size_t cells = cube(params_.nodeCells);
  timeStage(4, timeStages, [&] {
    attributes_.use();
    glDispatchCompute(workGroups(cells, 64), batch, 1);
  });
  timeStage(5, timeStages, [&] {
    faces_.use();
    glDispatchCompute(workGroups(cells, 64), batch, 1);
  });
}

Status StackQuadPipelineGpu::run(std::span<const NodeKey> nodes, bool timeStages,
                                 const std::function<void(std::size_t nodesDone)>& onBatch) {
  std::vector<NodeJob> jobs;
  jobs.reserve(nodes.size());
  for (const NodeKey& key : nodes) {
    if (key.x < 0 || key.y < 0 || key.z < 0 || key.x >= grid_.nodesX || key.y >= grid_.nodesY ||
        key.z >= grid_.nodesZ) {
      return makeError("node ({}, {}, {}) is outside the terrain's {} x {} x {} nodes", key.x,
                       key.y, key.z, grid_.nodesX, grid_.nodesY, grid_.nodesZ);
    }
    NodeJob job;
    job.origin = grid_.origin(key);
    jobs.push_back(job);
  }
  QuadCounters before;  // the counters before the batch (zero: the run starts empty)
  counters_.upload(0, sizeof before, &before);
  stageTimes_ = {};
  if (timeStages) gl::finish();
  attributes_.set("uVertexCapacity", int(vertexCapacity_));
  faces_.set("uIndexCapacity", int(indexCapacity_));
  attributes_.set("uWriteMorph", 0);
  attributes_.set("uSeamBandCells", 0);
  coarseA_.bindBase(GL_SHADER_STORAGE_BUFFER, kMorphTargets);  // bound, never written
  for (std::size_t first = 0; first < jobs.size(); first += std::size_t(batchNodes_)) {
    const std::size_t size = std::min(jobs.size() - first, std::size_t(batchNodes_));
    uploadJobs(std::span<const NodeJob>(jobs).subspan(first, size), true);
    for (int attempt = 0;; ++attempt) {
      countStages(size, timeStages);
      vertices_.bindBase(GL_SHADER_STORAGE_BUFFER, kVertices);
      indices_.bindBase(GL_SHADER_STORAGE_BUFFER, kIndices);
      writeStages(size, timeStages);
      glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
      counters_.download(0, sizeof counts_, &counts_);  // the seed's read-back, once a batch
      if (counts_.vertexCount <= vertexCapacity_ && counts_.indexCount <= indexCapacity_) break;
      if (attempt == 1) {
        return makeError("the quadrangulation outgrew its buffers twice in one batch ({} "
                         "vertices, {} indices)", counts_.vertexCount, counts_.indexCount);
      }
      // Overflowed (the kernels wrote nothing past the ends): grow by half again what is
      // needed, keeping the earlier batches' output, and redo this batch.
      ensureCapacity(counts_.vertexCount + counts_.vertexCount / 2,
                     counts_.indexCount + counts_.indexCount / 2, before.vertexCount,
                     before.indexCount);
      attributes_.set("uVertexCapacity", int(vertexCapacity_));
      faces_.set("uIndexCapacity", int(indexCapacity_));
      counters_.upload(0, sizeof before, &before);
    }
    before = counts_;
    if (onBatch) onBatch(first + size);
  }
  glMemoryBarrier(GL_COMMAND_BARRIER_BIT | GL_ELEMENT_ARRAY_BARRIER_BIT |
                  GL_VERTEX_ATTRIB_ARRAY_BARRIER_BIT);
  return {};
}

Status StackQuadPipelineGpu::makeBatch(std::span<const NodeJob> jobs, const StagingBuffers& staging,
                                       std::uint32_t firstPlacement) {
  if (!octree_) return makeError("makeBatch needs a pipeline over stack levels");
  if (jobs.empty() || jobs.size() > std::size_t(batchNodes_)) {
    return makeError("a batch holds 1 to {} nodes (got {})", batchNodes_, jobs.size());
  }
  if (!staging.vertices || !staging.indices || !staging.placements) {
    return makeError("makeBatch needs staging vertices, indices and placements");
  }
  const std::size_t placementsEnd = (1 + std::size_t(firstPlacement) + jobs.size()) * sizeof(NodePlacement);
  if (placementsEnd > staging.placements->size()) {
    return makeError("placements {} to {} lie past the {} bytes of their buffer", firstPlacement,
                     firstPlacement + jobs.size(), staging.placements->size());
  }
  const std::vector<QuadCounters> zero(jobs.size());
  counters_.upload(0, zero.size() * sizeof(QuadCounters), zero.data());
  uploadJobs(jobs, false);
  countStages(jobs.size(), false);
  // Placement: the nodes' firsts in the staging buffers, from the cursor.
  staging.placements->bindBase(GL_SHADER_STORAGE_BUFFER, kPlacements);
  place_.use();
  place_.set("uFirstPlacement", int(firstPlacement));
  place_.set("uStagingVertices", int(staging.vertexCapacity));
  place_.set("uStagingIndices", int(staging.indexCapacity));
  glDispatchCompute(1, 1, 1);
  glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
  attributes_.set("uVertexCapacity", int(staging.vertexCapacity));
  faces_.set("uIndexCapacity", int(staging.indexCapacity));
  staging.vertices->bindBase(GL_SHADER_STORAGE_BUFFER, kVertices);
  staging.indices->bindBase(GL_SHADER_STORAGE_BUFFER, kIndices);
  attributes_.set("uWriteMorph", staging.morphTargets ? 1 : 0);
  attributes_.set("uSeamBandCells", std::min(seamBandCells_, seamBandLimit(params_.nodeCells)));
  (staging.morphTargets ? *staging.morphTargets : coarseA_).bindBase(GL_SHADER_STORAGE_BUFFER, kMorphTargets);
  writeStages(jobs.size(), false);
  glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT | GL_SHADER_STORAGE_BARRIER_BIT);
  return {};
}

StackMesh StackQuadPipelineGpu::readMesh() const {
  StackMesh mesh;
  mesh.vertices.resize(counts_.vertexCount);
  mesh.indices.resize(counts_.indexCount);
  if (!mesh.vertices.empty()) {
    vertices_.download(0, mesh.vertices.size() * sizeof(StackVertex), mesh.vertices.data());
  }
  if (!mesh.indices.empty()) {
    indices_.download(0, mesh.indices.size() * sizeof(std::uint32_t), mesh.indices.data());
  }
  return mesh;
}

std::vector<CellEntry> StackQuadPipelineGpu::readCells(int slot) const {
  const std::size_t cells = cube(params_.nodeCells);
  std::vector<CellEntry> out(cells);
  cells_.download(std::size_t(slot) * cells * sizeof(CellEntry), cells * sizeof(CellEntry),
                  out.data());
  return out;
}

}  // namespace tellus
