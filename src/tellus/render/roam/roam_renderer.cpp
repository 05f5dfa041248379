#include "tellus/render/roam/roam_renderer.hpp"

#include <chrono>
#include <optional>

#include <spdlog/spdlog.h>

#include "tellus/lod/rag/rag_height_map.hpp"
#include "tellus/render/wireframe_overlay.hpp"

namespace tellus {

Result<std::unique_ptr<RoamRenderer>> RoamRenderer::create(const HeightGrid& grid, const RoamOptions& options) {
  Result<std::unique_ptr<roam::RoamMesh>> mesh = roam::RoamMesh::create(grid, options.settings);
  if (!mesh) return mesh.error();
  std::unique_ptr<RoamRenderer> renderer(new RoamRenderer());
  renderer->options_ = options;
  renderer->mesh_ = std::move(mesh.value());
  renderer->spacingXM_ = grid.spacingXM;
  renderer->spacingYM_ = grid.spacingYM;
  Result<FillAndWirePrograms> programs = loadFillAndWirePrograms("roam/roam.vert", "roam/roam.frag");
  if (!programs) return programs.error();
  renderer->fill_ = std::move(programs->fill);
  renderer->wire_ = std::move(programs->wire);
  // The shading texture: the grid, or the finest pyramid level that fits one texture.
  GLint maxTexture = 0;
  glGetIntegerv(GL_MAX_TEXTURE_SIZE, &maxTexture);
  const int level = rag::heightMapLevel(grid.width, grid.height, int(maxTexture));
  std::optional<rag::HeightMap> coarser;
  if (level > 0) {
    coarser = rag::heightMapAtLevel(grid, level);
    renderer->mapErrorM_ = coarser->errorM;
    renderer->mapStride_ = 1 << level;
    spdlog::info("ROAM: shading from level {} of the grid ({} x {}: beyond the texture limit)", level,
                 grid.width, grid.height);
  }
  const HeightGrid& map = coarser ? coarser->grid : grid;
  renderer->heights_ = gl::Texture::create2D(GL_R32F, map.width, map.height);
  renderer->heights_.upload2D(0, 0, 0, map.width, map.height, GL_RED, GL_FLOAT, map.heights.data());
  renderer->heights_.setFilter(GL_LINEAR, GL_LINEAR);
  renderer->heights_.setWrap(GL_CLAMP_TO_EDGE);
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
  const auto start = std::chrono::steady_clock::now();
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
  const double buildMs =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  drawStreamed(s, view, settings);
  ++framesDrawn_;
  FrameStats stats;
  stats.triangles = s.triangles;
  stats.vertices = s.triangles * 3;
  stats.drawCalls = s.triangles > 0 ? 1 : 0;
  stats.uploadBytes = bytes;
  stats.lodPriorityMs = report_.priorityMs;
  stats.lodRefineMs = report_.queueMs;
  stats.meshBuildMs = buildMs;
  return stats;
}

bool RoamRenderer::drawPreviousSelection(const ViewSetup& view, const RenderSettings& settings) {
  if (framesDrawn_ < 2) return false;
  drawStreamed(streamed_[std::size_t(1 - current_)], view, settings);
  return true;
}

void RoamRenderer::drawStreamed(const Streamed& streamed, const ViewSetup& view,
                                const RenderSettings& settings) {
  const glm::dvec3& eye = view.camera.position;
  const float exaggeration = settings.verticalExaggeration;
  for (const gl::Program* program : {&fill_, &wire_}) {
    program->set("uClipFromRelative", glm::mat4(view.relativeViewProjection()));
    program->set("uCameraGrid", glm::vec3(float(eye.x / spacingXM_), float(eye.y / spacingYM_),
                                          float(eye.z / double(exaggeration))));
    program->set("uGridScale", glm::vec3(float(spacingXM_), float(spacingYM_), exaggeration));
    program->set("uSpacing", glm::vec2(float(spacingXM_ * mapStride_), float(spacingYM_ * mapStride_)));
    program->set("uMapStride", float(mapStride_));
    program->set("uExaggeration", exaggeration);
  }
  fill_.set("uMapErrorM", mapErrorM_);
  applyShadingMode(fill_, view, settings);
  heights_.bindUnit(0);
  const auto drawWith = [&](const gl::Program& program) {
    if (streamed.triangles == 0) return;
    program.use();
    streamed.array.bind();
    glDrawArrays(GL_TRIANGLES, 0, GLsizei(streamed.triangles * 3));
  };
  drawWithWireframeOverlay(settings.wireframe, wire_, view, [&] { drawWith(fill_); },
                           [&] { drawWith(wire_); });
}

}  // namespace tellus
