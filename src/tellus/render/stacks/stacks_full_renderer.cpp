#include "tellus/render/stacks/stacks_full_renderer.hpp"

#include <algorithm>
#include <chrono>
#include <cstdint>

#include <spdlog/spdlog.h>

#include <fmt/format.h>

#include "tellus/core/progress.hpp"
#include "tellus/core/stopwatch.hpp"

namespace tellus {

Result<std::unique_ptr<StacksFullRenderer>> StacksFullRenderer::create(const StackTerrain& stacks,
                                                                       const StacksRenderOptions& options) {
  const Stopwatch start;
  Result<QuantisedStacks> quantised =
      QuantisedStacks::from(stacks, options.cellM > 0.0 ? options.cellM : stacks.spacingM());
  if (!quantised) return quantised.error();
  const std::vector<NodeKey> nodes = nodesWithSurface(quantised.value(), options.quad);
  Result<StackQuadPipelineGpu> pipeline =
      StackQuadPipelineGpu::create(quantised.value(), options.quad, 256);
  if (!pipeline) return pipeline.error();
  {
    Progress progress("stacks-full: quadrangulating every node", nodes.size());
    const auto advance = [&](std::size_t done) { progress.set(done); };
    if (Status ran = pipeline->run(nodes, false, advance); !ran) return ran.error();
  }
  std::unique_ptr<StacksFullRenderer> renderer(new StacksFullRenderer(std::move(pipeline.value())));
  Result<FillAndWirePrograms> programs =
      loadFillAndWirePrograms("stacks/stacks.vert", "stacks/stacks.frag");
  if (!programs) return programs.error();
  renderer->programs_ = std::move(programs.value());
  renderer->spacingM_ = float(stacks.spacingM());
  renderer->sky_.update(stacks);
  renderer->vertexArray_ = gl::VertexArray::create();
  renderer->vertexArray_.setIndexBuffer(renderer->pipeline_.indexBuffer());
  renderer->nodes_ = nodes.size();
  if (options.holeEvery > 0) {
    const std::uint32_t quads = renderer->quadCount();
    for (std::uint32_t first = 0; first < quads; first += options.holeEvery) {
      const std::uint32_t count = std::min(options.holeEvery - 1, quads - first);
      renderer->rangeCounts_.push_back(GLsizei(6 * count));
      renderer->rangeOffsets_.push_back(
          reinterpret_cast<const void*>(std::uintptr_t(first) * 6 * sizeof(std::uint32_t)));
    }
  }
  renderer->buildSeconds_ =
      start.elapsedS();
  spdlog::info("stacks-full: {} nodes of {}^3 cells quadrangulated into {} quads in {:.2f} s",
               nodes.size(), options.quad.nodeCells, renderer->quadCount(), renderer->buildSeconds_);
  return renderer;
}

FrameStats StacksFullRenderer::draw(const ViewSetup& view, const RenderSettings& settings) {
  FrameStats stats;
  applyShadingMode(programs_.fill, view, settings);
  if (settings.imagery) sky_.apply(programs_.fill);
  for (const gl::Program* program : {&programs_.fill, &programs_.wire}) {
    program->set("uViewProjection", glm::mat4(view.relativeViewProjection()));
    program->set("uCameraPosition", glm::vec3(view.camera.position));
    program->set("uExaggeration", settings.verticalExaggeration);
  }
  programs_.wire.set("uSpacing", glm::vec2(spacingM_));
  // The pipeline's buffers can grow (reallocate) on a rebuild: rebind every frame.
  vertexArray_.setIndexBuffer(pipeline_.indexBuffer());
  const auto drawMesh = [&] {
    vertexArray_.bind();
    pipeline_.vertexBuffer().bindBase(GL_SHADER_STORAGE_BUFFER, 0);
    // The surface is closed and wound counter-clockwise seen from the air: back faces are never
    // seen from outside the solid, and culling them lets a hole show the sky behind the terrain
    // (where the crack metric finds it) instead of the inside of the solid.
    glEnable(GL_CULL_FACE);
    glCullFace(culledFaces_);
    if (!rangeCounts_.empty()) {
      glMultiDrawElements(GL_TRIANGLES, rangeCounts_.data(), GL_UNSIGNED_INT, rangeOffsets_.data(),
                          GLsizei(rangeCounts_.size()));
    } else {
      glBindBuffer(GL_DRAW_INDIRECT_BUFFER, pipeline_.counterBuffer().id());
      glDrawElementsIndirect(GL_TRIANGLES, GL_UNSIGNED_INT, nullptr);
      glBindBuffer(GL_DRAW_INDIRECT_BUFFER, 0);
    }
    glDisable(GL_CULL_FACE);
  };
  drawWithWireframeOverlay(
      settings.wireframe, programs_.wire, view,
      [&] {
        programs_.fill.use();
        drawMesh();
      },
      [&] {
        programs_.wire.use();
        drawMesh();
      });
  stats.triangles = pipeline_.indexCount() / 3;
  stats.vertices = pipeline_.vertexCount();
  stats.drawCalls = settings.wireframe ? 2 : 1;
  return stats;
}

bool StacksFullRenderer::drawLastFrameBackFaces(const ViewSetup& view,
                                                const RenderSettings& settings) {
  RenderSettings fillOnly = settings;
  fillOnly.wireframe = false;
  culledFaces_ = GL_FRONT;
  draw(view, fillOnly);
  culledFaces_ = GL_BACK;
  return true;
}

std::vector<std::string> StacksFullRenderer::frameReport() const {
  return {fmt::format("{} nodes, {} quads, built in {:.2f} s", nodes_, quadCount(), buildSeconds_)};
}

}  // namespace tellus
