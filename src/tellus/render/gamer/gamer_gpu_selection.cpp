#include "tellus/render/gamer/gamer_gpu_selection.hpp"

#include <array>
#include <vector>

#include "tellus/gl/gpu_wait.hpp"

namespace tellus {
namespace {

// The passes' storage buffers, bound at once in this order (gamer_select_common.glsl).
constexpr GLuint kBindings = 10;

struct DrawCommand {  // DrawElementsIndirectCommand
  std::uint32_t count, instanceCount, firstIndex, baseVertex, baseInstance;
};

GLuint groupsOf(std::size_t invocations) { return gl::workGroups(invocations, 64); }

}  // namespace

Result<GamerGpuSelection> GamerGpuSelection::create(const gamer::CoarseTerrain& terrain,
                                                    const gamer::PatternPool& pool) {
  GamerGpuSelection s;
  if (Status built = gl::buildComputePrograms({{&s.classify_, "gamer/classify.comp"},
                                                {&s.scatter_, "gamer/scatter.comp"}});
      !built) {
    return built.error();
  }
  s.cellsX_ = terrain.cellsX();
  s.cellsY_ = terrain.cellsY();
  s.maxDepth_ = terrain.maxDepth();
  s.patternCount_ = int(pool.patterns.size());
  const HeightGrid& grid = terrain.grid();
  std::vector<glm::vec4> points;
  for (int j = 0; j <= s.cellsY_; ++j) {
    for (int i = 0; i <= s.cellsX_; ++i) {
      const glm::ivec2 p = terrain.vertexSample(i, j);
      points.emplace_back(float(p.x * grid.spacingXM), float(p.y * grid.spacingYM),
                          grid.at(p.x, grid.height - 1 - p.y), 0.0f);
    }
  }
  std::vector<glm::vec2> heights;
  for (const HeightRange& h : terrain.cellHeights()) heights.emplace_back(h.minM, h.maxM);
  std::vector<glm::uvec2> patterns;
  for (const gamer::PatternRange& p : pool.patterns) patterns.emplace_back(p.indexCount, p.firstIndex);
  s.points_ = gl::Buffer(std::span<const glm::vec4>(points));
  s.errors_ = gl::Buffer(std::span<const float>(terrain.vertexErrors()));
  const std::uint32_t noGroupDone = 0;
  s.groupsDone_ = gl::Buffer(sizeof noGroupDone, &noGroupDone);
  s.cellHeights_ = gl::Buffer(std::span<const glm::vec2>(heights));
  s.patterns_ = gl::Buffer(std::span<const glm::uvec2>(patterns));
  const std::vector<std::uint32_t> noCounts(patterns.size(), 0u);  // the passes leave them at 0
  s.counts_ = gl::Buffer(std::span<const std::uint32_t>(noCounts));
  // Per coarse triangle: pattern, rank, instance (std430: 32 bytes).
  s.chosen_ = gl::Buffer(std::size_t(2) * std::size_t(s.cellsX_) * std::size_t(s.cellsY_) * 2 * sizeof(glm::uvec4), nullptr);
  s.classify_.set("uRadiusM", float(terrain.cellRadiusM()));
  for (const gl::Program* program : {&s.classify_, &s.scatter_}) {
    program->set("uMaxDepth", s.maxDepth_);
    program->set("uCellsX", s.cellsX_);
    program->set("uCellsY", s.cellsY_);
    program->set("uPatternCount", s.patternCount_);
  }
  return s;
}

GamerGpuSelection::Output GamerGpuSelection::makeOutput() const {
  Output out;
  out.commands = gl::Buffer(std::size_t(patternCount_) * sizeof(DrawCommand), nullptr);
  out.instances = gl::Buffer(std::size_t(2) * std::size_t(cellsX_) * std::size_t(cellsY_) * sizeof(gamer::Instance), nullptr);
  out.stats = gl::Buffer(sizeof(glm::uvec4), nullptr);
  return out;
}

void GamerGpuSelection::run(const LodView& view, const gamer::GamerSettings& settings, Output& out) {
  const std::array<GLuint, kBindings> buffers{points_.id(),      errors_.id(),         groupsDone_.id(),
                                              cellHeights_.id(), patterns_.id(),       counts_.id(),
                                              chosen_.id(),      out.commands.id(),    out.instances.id(),
                                              out.stats.id()};
  glBindBuffersBase(GL_SHADER_STORAGE_BUFFER, 0, kBindings, buffers.data());

  // Every cell's corners' tags and its triangles' patterns, counted; then (the last group) the
  // commands.
  classify_.use();
  classify_.set("uEye", glm::vec4(glm::vec3(view.cameraM), view.exaggeration));
  classify_.set("uProjection", glm::vec2(float(double(view.exaggeration) * view.pixelsPerRadian), float(view.nearM)));
  if (settings.targetPx != targetPx_ || settings.morphBand != morphBand_ || settings.culling != culling_) {
    classify_.set("uTargetPx", settings.targetPx);
    classify_.set("uMorphBand", settings.morphBand);
    classify_.set("uCulling", settings.culling ? 1 : 0);
    targetPx_ = settings.targetPx;
    morphBand_ = settings.morphBand;
    culling_ = settings.culling;
  }
  std::array<glm::vec4, 6> planes{};
  for (std::size_t k = 0; k < 6; ++k) planes[k] = glm::vec4(view.frustum.planes()[k]);
  classify_.setArray("uPlanes", planes.data(), 6);
  glDispatchCompute(groupsOf(std::size_t(cellsX_) * std::size_t(cellsY_)), 1, 1);
  glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);

  scatter_.use();
  glDispatchCompute(groupsOf(std::size_t(2) * std::size_t(cellsX_) * std::size_t(cellsY_)), 1, 1);
  glMemoryBarrier(GL_COMMAND_BARRIER_BIT | GL_VERTEX_ATTRIB_ARRAY_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT |
                  GL_SHADER_STORAGE_BARRIER_BIT);
  out.ran = gl::Fence::insert();
}

std::optional<GamerGpuSelection::Totals> GamerGpuSelection::totalsIfDone(Output& out) {
  if (!out.ran.valid() || !out.ran.passed()) return std::nullopt;
  glm::uvec4 totals{0};
  gl::readCompletedBuffer(out.stats.id(), 0, sizeof totals, &totals);
  return Totals{totals.x, totals.y, totals.z};
}

GamerGpuSelection::Totals GamerGpuSelection::readTotals(Output& out) {
  out.ran.wait();
  return *totalsIfDone(out);
}

gamer::Selection GamerGpuSelection::readSelection(const Output& out) const {
  std::vector<DrawCommand> commands(static_cast<std::size_t>(patternCount_));
  gl::readBuffer(out.commands.id(), 0, commands.size() * sizeof(DrawCommand), commands.data());
  gamer::Selection s;
  std::uint32_t total = 0;
  for (const DrawCommand& c : commands) {
    s.firstInstance.push_back(c.baseInstance);
    s.instanceCount.push_back(c.instanceCount);
    s.triangles += std::uint64_t(c.instanceCount) * (c.count / 3);
    total += c.instanceCount;
  }
  s.coarseTriangles = total;
  s.instances.resize(total);
  if (total > 0) gl::readBuffer(out.instances.id(), 0, total * sizeof(gamer::Instance), s.instances.data());
  return s;
}

}  // namespace tellus
