#include "tellus/render/giw/giw_gpu_warp.hpp"

#include <array>

#include <glm/vec2.hpp>
#include <glm/vec4.hpp>

namespace tellus {
namespace {

// The passes' storage buffers, bound at once in this order (giw_warp_common.glsl, warp_rows.comp).
constexpr GLuint kFirstBinding = 0, kBindings = 7;

// Work groups of `local` invocations covering `invocations` (sizes here are ints).
GLuint groups(int invocations, int local) { return gl::workGroups(std::size_t(invocations), std::size_t(local)); }

}  // namespace

Result<GiwGpuWarp> GiwGpuWarp::create(int size) {
  GiwGpuWarp w;
  w.size_ = size;
  if (Status built = gl::buildComputePrograms({{&w.rows_, "giw/warp_rows.comp"},
                                                {&w.resample_, "giw/resample.comp"}});
      !built) {
    return built.error();
  }
  for (const gl::Program* program : {&w.rows_, &w.resample_}) program->set("uSize", size);
  const std::size_t samples = std::size_t(size) * std::size_t(size);
  w.importanceMap_ = gl::Buffer(samples * sizeof(float), nullptr);
  w.rowX_ = gl::Buffer(samples * sizeof(float), nullptr);
  w.rowTotals_ = gl::Buffer(std::size_t(size) * sizeof(float), nullptr);
  w.cumulative_ = gl::Buffer((samples + std::size_t(size)) * sizeof(float), nullptr);
  w.columnT_ = gl::Buffer(std::size_t(size) * sizeof(float), nullptr);
  const std::uint32_t noRowDone = 0;
  w.rowsDone_ = gl::Buffer(sizeof noRowDone, &noRowDone);
  return w;
}

void GiwGpuWarp::run(const gl::Texture& heights, const HeightGrid& grid, const giw::Region& region,
                     const LodView& view, const giw::GiwSettings& settings, const gl::Buffer& vertices) {
  heights.bindUnit(0);
  const std::array<GLuint, kBindings> buffers{importanceMap_.id(), rowX_.id(),     rowTotals_.id(), cumulative_.id(),
                                              columnT_.id(),       vertices.id(), rowsDone_.id()};
  glBindBuffersBase(GL_SHADER_STORAGE_BUFFER, kFirstBinding, kBindings, buffers.data());
  const glm::vec2 regionMin(region.min), step((region.max - region.min) / double(size_ - 1));
  const glm::vec4 regionUniform(regionMin, step);
  const Constants constants{glm::vec2(float(grid.spacingXM), float(grid.spacingYM)), settings.slopeWeight,
                            settings.outsideImportance, settings.uniformShare};
  if (!constantsSet_ || !(constants == constants_)) {
    rows_.set("uSpacing", constants.spacing);
    rows_.set("uSlopeWeight", constants.slopeWeight);
    rows_.set("uOutsideImportance", constants.outsideImportance);
    rows_.set("uUniformShare", constants.uniformShare);
    constants_ = constants;
    constantsSet_ = true;
  }

  // Each row's importance and warp, then (its last group) the columns'.
  rows_.use();
  rows_.set("uRegion", regionUniform);
  rows_.set("uEye", glm::vec4(glm::vec3(view.cameraM), view.exaggeration));
  rows_.set("uNearM", float(view.nearM));
  std::array<glm::vec4, 6> planes{};
  for (std::size_t k = 0; k < 6; ++k) planes[k] = glm::vec4(view.frustum.planes()[k]);
  rows_.setArray("uPlanes", planes.data(), 6);
  glDispatchCompute(GLuint(size_), 1, 1);
  glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);

  resample_.use();
  resample_.set("uRegion", regionUniform);
  glDispatchCompute(groups(size_, 8), groups(size_, 8), 1);
  glMemoryBarrier(GL_VERTEX_ATTRIB_ARRAY_BARRIER_BIT | GL_SHADER_STORAGE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
}

}  // namespace tellus
