#include "tellus/render/giw/giw_gpu_warp.hpp"

#include <array>

#include <glm/vec2.hpp>
#include <glm/vec4.hpp>

namespace tellus {
namespace {

constexpr GLuint kImportance = 0, kRowX = 1, kRowTotals = 2, kCumulative = 3, kColumnT = 4, kVertices = 5;

// Work groups of `local` invocations covering `invocations` (sizes here are ints).
GLuint groups(int invocations, int local) { return gl::workGroups(std::size_t(invocations), std::size_t(local)); }

}  // namespace

Result<GiwGpuWarp> GiwGpuWarp::create(int size) {
  GiwGpuWarp w;
  w.size_ = size;
  if (Status built = gl::buildComputePrograms({{&w.importance_, "giw/importance.comp"},
                                                {&w.rows_, "giw/warp_rows.comp"},
                                                {&w.columns_, "giw/warp_columns.comp"},
                                                {&w.resample_, "giw/resample.comp"}});
      !built) {
    return built.error();
  }
  for (const gl::Program* program : {&w.importance_, &w.rows_, &w.columns_, &w.resample_}) program->set("uSize", size);
  const std::size_t samples = std::size_t(size) * std::size_t(size);
  w.importanceMap_ = gl::Buffer(samples * sizeof(float), nullptr);
  w.rowX_ = gl::Buffer(samples * sizeof(float), nullptr);
  w.rowTotals_ = gl::Buffer(std::size_t(size) * sizeof(float), nullptr);
  w.cumulative_ = gl::Buffer((samples + std::size_t(size)) * sizeof(float), nullptr);
  w.columnT_ = gl::Buffer(std::size_t(size) * sizeof(float), nullptr);
  return w;
}

void GiwGpuWarp::run(const gl::Texture& heights, const HeightGrid& grid, const giw::Region& region,
                     const LodView& view, const giw::GiwSettings& settings, const gl::Buffer& vertices) {
  heights.bindUnit(0);
  importanceMap_.bindBase(GL_SHADER_STORAGE_BUFFER, kImportance);
  rowX_.bindBase(GL_SHADER_STORAGE_BUFFER, kRowX);
  rowTotals_.bindBase(GL_SHADER_STORAGE_BUFFER, kRowTotals);
  cumulative_.bindBase(GL_SHADER_STORAGE_BUFFER, kCumulative);
  columnT_.bindBase(GL_SHADER_STORAGE_BUFFER, kColumnT);
  vertices.bindBase(GL_SHADER_STORAGE_BUFFER, kVertices);
  const glm::vec2 regionMin(region.min), step((region.max - region.min) / double(size_ - 1));

  importance_.use();
  importance_.set("uRegionMin", regionMin);
  importance_.set("uStep", step);
  importance_.set("uSpacing", glm::vec2(float(grid.spacingXM), float(grid.spacingYM)));
  importance_.set("uCamera", glm::vec3(view.cameraM));
  importance_.set("uExaggeration", view.exaggeration);
  importance_.set("uNearM", float(view.nearM));
  importance_.set("uSlopeWeight", settings.slopeWeight);
  importance_.set("uOutsideImportance", settings.outsideImportance);
  std::array<glm::vec4, 6> planes{};
  for (std::size_t k = 0; k < 6; ++k) planes[k] = glm::vec4(view.frustum.planes()[k]);
  importance_.setArray("uPlanes", planes.data(), 6);
  glDispatchCompute(groups(size_, 8), groups(size_, 8), 1);
  glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);

  rows_.use();
  rows_.set("uUniformShare", settings.uniformShare);
  glDispatchCompute(groups(size_, 64), 1, 1);
  glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);

  columns_.use();
  columns_.set("uUniformShare", settings.uniformShare);
  glDispatchCompute(1, 1, 1);
  glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);

  resample_.use();
  resample_.set("uRegionMin", regionMin);
  resample_.set("uStep", step);
  glDispatchCompute(groups(size_, 8), groups(size_, 8), 1);
  glMemoryBarrier(GL_VERTEX_ATTRIB_ARRAY_BARRIER_BIT | GL_SHADER_STORAGE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
}

}  // namespace tellus
