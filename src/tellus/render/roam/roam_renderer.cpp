#include "tellus/render/roam/roam_renderer.hpp"


#include <spdlog/spdlog.h>

#include <fmt/format.h>

#include "tellus/core/stopwatch.hpp"

namespace tellus {

Result<std::unique_ptr<RoamRenderer>> RoamRenderer::create(const HeightGrid& grid, const RoamOptions& options) {
  Result<std::unique_ptr<roam::RoamMesh>> mesh = roam::RoamMesh::create(grid, options.settings);
  if (!mesh) return mesh.error();
  std::unique_ptr<RoamRenderer> renderer(new RoamRenderer());
  renderer->options_ = options;
  renderer->mesh_ = std::move(mesh.value());
  Result<GridMeshShading> shading = GridMeshShading::create(grid, "roam/roam.vert", "ROAM");
  if (!shading) return shading.error();
  renderer->shading_ = std::move(shading.value());
  for (Streamed& s : renderer->streamed_) s.array = gl::VertexArray::create();
  return renderer;
}

void RoamRenderer::prepare(const ViewSetup& view, const RenderSettings& settings) {
  report_ = mesh_->update(roam::RoamView::fromSetup(view, settings.verticalExaggeration));
  prepared_ = true;
  spdlog::debug("roam: {} leaves, {} splits, {} merges, {} re-prioritised ({:.2f} + {:.2f} ms)",
                report_.leaves, report_.splits, report_.merges, report_.reprioritised,
                report_.priorityMs, report_.queueMs);
}

FrameStats RoamRenderer::draw(const ViewSetup& view, const RenderSettings& settings) {
  if (!prepared_) prepare(view, settings);  // a caller that does not prepare (stills)
  prepared_ = false;
  // Submission: the visible leaves into the other buffer (the last frame's stays for popping).
  const Stopwatch build;
  current_ = 1 - current_;
  Streamed& s = streamed_[std::size_t(current_)];
  // The leaves go straight into the buffer, mapped for writing with its old contents dropped
  // (no copy; the driver need not wait for the frame that last drew from it).
  const std::size_t room = std::size_t(mesh_->leafCount()) * 3 * sizeof(glm::vec4);
  if (room > s.capacityBytes) {
    s.capacityBytes = std::max<std::size_t>(room + room / 2, std::size_t(1) << 20);
    s.buffer = gl::Buffer(s.capacityBytes, nullptr, GL_MAP_WRITE_BIT);
    // One attribute: (u, v, height, level).
    glVertexArrayVertexBuffer(s.array.id(), 0, s.buffer.id(), 0, GLsizei(sizeof(glm::vec4)));
    glEnableVertexArrayAttrib(s.array.id(), 0);
    glVertexArrayAttribFormat(s.array.id(), 0, 4, GL_FLOAT, GL_FALSE, 0);
    glVertexArrayAttribBinding(s.array.id(), 0, 0);
  }
  auto* mapped = static_cast<glm::vec4*>(glMapNamedBufferRange(
      s.buffer.id(), 0, GLsizeiptr(room), GL_MAP_WRITE_BIT | GL_MAP_INVALIDATE_BUFFER_BIT));
  s.triangles = mapped ? mesh_->emit(mapped) : 0;
  if (mapped) glUnmapNamedBuffer(s.buffer.id());
  const std::size_t bytes = s.triangles * 3 * sizeof(glm::vec4);
  const double buildMs = build.elapsedMs();
  drawStreamed(s, view, settings);
  ++framesDrawn_;
  FrameStats stats;
  stats.triangles = s.triangles;
  stats.vertices = s.triangles * 3;
  stats.drawCalls = s.triangles > 0 ? 1 : 0;
  stats.uploadBytes = bytes;
  // prepare()'s two halves (re-prioritising, splitting and merging) and draw()'s mesh build.
  stats.stageMs = {{"lod_priority", report_.priorityMs},
                   {"lod_refine", report_.queueMs},
                   {"mesh_build", buildMs}};
  return stats;
}

bool RoamRenderer::drawPreviousSelection(const ViewSetup& view, const RenderSettings& settings) {
  if (framesDrawn_ < 2) return false;
  drawStreamed(streamed_[std::size_t(1 - current_)], view, settings);
  return true;
}

void RoamRenderer::drawStreamed(const Streamed& streamed, const ViewSetup& view,
                                const RenderSettings& settings) {
  shading_.draw(view, settings, [&](const gl::Program& program) {
    if (streamed.triangles == 0) return;
    program.use();
    streamed.array.bind();
    glDrawArrays(GL_TRIANGLES, 0, GLsizei(streamed.triangles * 3));
  });
}

std::vector<std::string> RoamRenderer::frameReport() const {
  const roam::RoamFrameReport& r = report_;
  return {fmt::format("leaves {}, diamonds {}", countText(r.leaves), countText(r.diamonds)),
          fmt::format("splits {}, merges {}, re-prioritised {}", r.splits, r.merges,
                      countText(r.reprioritised)),
          fmt::format("priorities {:.2f} ms, splits/merges {:.2f} ms", r.priorityMs, r.queueMs),
          fmt::format("top of split queue {:.2f} px{}{}", r.maxSplitPriorityPx,
                      r.budgetReached ? ", budget reached" : "", r.timeReached ? ", time reached" : ""),
          fmt::format("error bounds {:.1f} MB", double(mesh_->boundsBytes()) / 1e6)};
}

}  // namespace tellus
