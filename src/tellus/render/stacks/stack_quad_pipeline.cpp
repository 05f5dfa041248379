#include "tellus/render/stacks/stack_quad_pipeline.hpp"

#include <algorithm>
#include <array>
#include <chrono>

#include <glm/vec3.hpp>

namespace tellus {
namespace {

constexpr GLuint kOffsets = 0, kLayers = 1, kOrigins = 2, kVolumeIn = 3, kVolumeOut = 4,
                 kCells = 5, kCounters = 6, kVertices = 7, kIndices = 8;

GLuint groups(std::size_t invocations, std::size_t local) {
  return GLuint((invocations + local - 1) / local);
}

Result<gl::Program> computeProgram(const char* file) {
  return gl::Program::fromFiles({{GL_COMPUTE_SHADER, file}});
}

}  // namespace

Result<StackQuadPipelineGpu> StackQuadPipelineGpu::create(const QuantisedStacks& stacks,
                                                          const QuadParams& params,
                                                          int batchNodes) {
  if (Status ok = params.check(); !ok) return ok.error();
  if (batchNodes < 1 || batchNodes > 4096) {
    return makeError("nodes per batch must be 1 to 4096 (got {})", batchNodes);
  }
  if (stacks.layers.size() >= (std::size_t(1) << 31) / sizeof(QuantisedLayer)) {
    return makeError("{} layers do not fit one GPU buffer", stacks.layers.size());
  }
  StackQuadPipelineGpu p;
  p.params_ = params;
  p.grid_ = NodeGrid::of(stacks, params);
  p.batchNodes_ = batchNodes;
  p.stacksShape_.width = stacks.width;
  p.stacksShape_.height = stacks.height;
  p.stacksShape_.cellsZ = stacks.cellsZ;
  p.stacksShape_.spacingM = stacks.spacingM;
  p.stacksShape_.cellM = stacks.cellM;
  const std::array<std::pair<gl::Program*, const char*>, 6> programs{{
      {&p.density_, "stacks/density.comp"},
      {&p.smooth_, "stacks/smooth.comp"},
      {&p.classify_, "stacks/classify.comp"},
      {&p.allocate_, "stacks/allocate.comp"},
      {&p.attributes_, "stacks/attributes.comp"},
      {&p.faces_, "stacks/faces.comp"},
  }};
  for (const auto& [program, file] : programs) {
    Result<gl::Program> built = computeProgram(file);
    if (!built) return built.error();
    *program = std::move(built.value());
  }
  // An empty terrain still needs non-empty buffers to bind.
  const QuantisedLayer none{};
  p.offsets_ = gl::Buffer(std::span<const std::uint32_t>(stacks.offsets));
  p.layers_ = stacks.layers.empty() ? gl::Buffer(sizeof none, &none)
                                    : gl::Buffer(std::span<const QuantisedLayer>(stacks.layers));
  p.origins_ = gl::Buffer(std::size_t(batchNodes) * 16, nullptr, GL_DYNAMIC_STORAGE_BIT);
  const std::size_t raw = std::size_t(params.rawSide()) * params.rawSide() * params.rawSide();
  p.volumeA_ = gl::Buffer(std::size_t(batchNodes) * raw * 16, nullptr);
  p.volumeB_ = gl::Buffer(std::size_t(batchNodes) * raw * 16, nullptr);
  const std::size_t cells = std::size_t(params.nodeCells) * params.nodeCells * params.nodeCells;
  p.cells_ = gl::Buffer(std::size_t(batchNodes) * cells * sizeof(CellEntry), nullptr,
                        GL_DYNAMIC_STORAGE_BIT);
  p.counters_ = gl::Buffer(sizeof(QuadCounters), nullptr, GL_DYNAMIC_STORAGE_BIT);

  const std::vector<std::uint32_t> taps = params.filterTaps();
  std::array<int, 9> tapValues{};
  for (std::size_t t = 0; t < taps.size(); ++t) tapValues[t] = int(taps[t]);
  for (gl::Program* program : {&p.density_, &p.smooth_, &p.classify_, &p.allocate_,
                               &p.attributes_, &p.faces_}) {
    program->set("uNodeCells", params.nodeCells);
    program->set("uFilterRadius", params.filterRadius);
    program->set("uRawSide", params.rawSide());
    program->set("uSmoothSide", params.smoothSide());
  }
  p.density_.set("uStackSize", glm::ivec2(stacks.width, stacks.height));
  p.smooth_.setArray("uTaps", tapValues.data(), int(tapValues.size()));
  p.classify_.set("uIsoTwice", int(params.isoTwice()));
  p.attributes_.set("uIsoTwice", int(params.isoTwice()));
  p.attributes_.set("uSpacing", float(stacks.spacingM));
  p.attributes_.set("uCellM", float(stacks.cellM));
  p.ensureCapacity(1024, 6 * 1024, 0, 0);
  return p;
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
  attributes_.set("uVertexCapacity", int(vertexCapacity_));
  faces_.set("uIndexCapacity", int(indexCapacity_));
  vertices_.bindBase(GL_SHADER_STORAGE_BUFFER, kVertices);
  indices_.bindBase(GL_SHADER_STORAGE_BUFFER, kIndices);
}

void StackQuadPipelineGpu::dispatchBatch(std::span<const NodeKey> batch, bool timeStages) {
  std::vector<std::array<int, 4>> origins;
  for (const NodeKey& key : batch) {
    const std::array<int, 3> o = grid_.origin(key);
    origins.push_back({o[0], o[1], o[2], 0});
  }
  origins_.upload(0, origins.size() * sizeof(origins[0]), origins.data());
  const auto count = GLuint(batch.size());
  for (gl::Program* program : {&density_, &smooth_, &classify_, &allocate_, &attributes_, &faces_}) {
    program->set("uBatchCount", int(count));
  }
  // Timed stages end in glFinish and are timed on the CPU clock: software rasterisers (Mesa's
  // llvmpipe) report no time for compute dispatches in GL_TIME_ELAPSED queries.
  int stageIndex = 0;
  const auto stage = [&](auto&& body) {
    const auto start = std::chrono::steady_clock::now();
    body();
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    if (timeStages) {
      glFinish();
      const double ms =
          std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
      double* slots[] = {&stageTimes_.density, &stageTimes_.smooth,     &stageTimes_.classify,
                         &stageTimes_.allocate, &stageTimes_.attributes, &stageTimes_.faces};
      *slots[stageIndex] += ms;
    }
    ++stageIndex;
  };
  const int n = params_.nodeCells;
  const int raw = params_.rawSide();
  const std::size_t cells = std::size_t(n) * n * n;

  stage([&] {  // density
    volumeA_.bindBase(GL_SHADER_STORAGE_BUFFER, kVolumeIn);
    density_.use();
    glDispatchCompute(groups(std::size_t(raw), 8), groups(std::size_t(raw), 8), count);
  });
  stage([&] {  // smooth: A -> B (x), B -> A (y), A -> B (z)
    smooth_.use();
    glm::ivec3 size(raw, raw, raw);
    for (int axis = 0; axis < 3; ++axis) {
      const gl::Buffer& in = axis == 1 ? volumeB_ : volumeA_;
      const gl::Buffer& out = axis == 1 ? volumeA_ : volumeB_;
      in.bindBase(GL_SHADER_STORAGE_BUFFER, kVolumeIn);
      out.bindBase(GL_SHADER_STORAGE_BUFFER, kVolumeOut);
      smooth_.set("uAxis", axis);
      smooth_.set("uInSize", size);
      size[axis] -= 2 * params_.filterRadius;
      glDispatchCompute(groups(std::size_t(size.x) * size.y * size.z, 64), count, 1);
      if (axis < 2) glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    }
    volumeB_.bindBase(GL_SHADER_STORAGE_BUFFER, kVolumeOut);  // the smoothed density
  });
  stage([&] {
    classify_.use();
    glDispatchCompute(groups(cells, 64), count, 1);
  });
  stage([&] {
    allocate_.use();
    glDispatchCompute(groups(std::size_t(n) * n, 64), count, 1);
  });
  stage([&] {
    attributes_.use();
    glDispatchCompute(groups(cells, 64), count, 1);
  });
  stage([&] {
    faces_.use();
    glDispatchCompute(groups(cells, 64), count, 1);
  });
}

Status StackQuadPipelineGpu::run(std::span<const NodeKey> nodes, bool timeStages) {
  for (const NodeKey& key : nodes) {
    if (key.x < 0 || key.y < 0 || key.z < 0 || key.x >= grid_.nodesX || key.y >= grid_.nodesY ||
        key.z >= grid_.nodesZ) {
      return makeError("node ({}, {}, {}) is outside the terrain's {} x {} x {} nodes", key.x,
                       key.y, key.z, grid_.nodesX, grid_.nodesY, grid_.nodesZ);
    }
  }
  QuadCounters before;  // the counters before the batch (zero: the run starts empty)
  counters_.upload(0, sizeof before, &before);
  offsets_.bindBase(GL_SHADER_STORAGE_BUFFER, kOffsets);
  layers_.bindBase(GL_SHADER_STORAGE_BUFFER, kLayers);
  origins_.bindBase(GL_SHADER_STORAGE_BUFFER, kOrigins);
  cells_.bindBase(GL_SHADER_STORAGE_BUFFER, kCells);
  counters_.bindBase(GL_SHADER_STORAGE_BUFFER, kCounters);
  vertices_.bindBase(GL_SHADER_STORAGE_BUFFER, kVertices);
  indices_.bindBase(GL_SHADER_STORAGE_BUFFER, kIndices);
  stageTimes_ = {};
  if (timeStages) glFinish();
  for (std::size_t first = 0; first < nodes.size(); first += std::size_t(batchNodes_)) {
    const std::size_t size = std::min(nodes.size() - first, std::size_t(batchNodes_));
    for (int attempt = 0;; ++attempt) {
      dispatchBatch(nodes.subspan(first, size), timeStages);
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
      counters_.upload(0, sizeof before, &before);
    }
    before = counts_;
  }
  glMemoryBarrier(GL_COMMAND_BARRIER_BIT | GL_ELEMENT_ARRAY_BARRIER_BIT |
                  GL_VERTEX_ATTRIB_ARRAY_BARRIER_BIT);
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
  const std::size_t cells = std::size_t(params_.nodeCells) * params_.nodeCells * params_.nodeCells;
  std::vector<CellEntry> out(cells);
  cells_.download(std::size_t(slot) * cells * sizeof(CellEntry), cells * sizeof(CellEntry),
                  out.data());
  return out;
}

}  // namespace tellus
