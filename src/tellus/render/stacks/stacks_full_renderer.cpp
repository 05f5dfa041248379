#include "tellus/render/stacks/stacks_full_renderer.hpp"

#include <chrono>

#include <spdlog/spdlog.h>

namespace tellus {

Result<std::unique_ptr<StacksFullRenderer>> StacksFullRenderer::create(const StackTerrain& stacks,
                                                                       const StacksRenderOptions& options) {
  const auto start = std::chrono::steady_clock::now();
  Result<QuantisedStacks> quantised =
      QuantisedStacks::from(stacks, options.cellM > 0.0 ? options.cellM : stacks.spacingM());
  if (!quantised) return quantised.error();
  const std::vector<NodeKey> nodes = nodesWithSurface(quantised.value(), options.quad);
  Result<StackQuadPipelineGpu> pipeline =
      StackQuadPipelineGpu::create(quantised.value(), options.quad, 256);
  if (!pipeline) return pipeline.error();
  if (Status ran = pipeline->run(nodes); !ran) return ran.error();
  std::unique_ptr<StacksFullRenderer> renderer(new StacksFullRenderer(std::move(pipeline.value())));
  Result<gl::Program> program = gl::Program::fromFiles(
      {{GL_VERTEX_SHADER, "stacks/stacks.vert"}, {GL_FRAGMENT_SHADER, "stacks/stacks.frag"}});
  if (!program) return program.error();
  renderer->program_ = std::move(program.value());
  renderer->vertexArray_ = gl::VertexArray::create();
  renderer->vertexArray_.setIndexBuffer(renderer->pipeline_.indexBuffer());
  renderer->nodes_ = nodes.size();
  renderer->buildSeconds_ =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  spdlog::info("stacks-full: {} nodes of {}^3 cells quadrangulated into {} quads in {:.2f} s",
               nodes.size(), options.quad.nodeCells, renderer->quadCount(), renderer->buildSeconds_);
  return renderer;
}

FrameStats StacksFullRenderer::draw(const ViewSetup& view, const RenderSettings& settings) {
  FrameStats stats;
  applyShading(program_, settings.shading);
  program_.set("uViewProjection", glm::mat4(view.relativeViewProjection()));
  program_.set("uCameraPosition", glm::vec3(view.camera.position));
  program_.set("uExaggeration", settings.verticalExaggeration);
  program_.use();
  // The pipeline's vertex buffer can grow (reallocate) on a rebuild: rebind every frame.
  vertexArray_.setIndexBuffer(pipeline_.indexBuffer());
  vertexArray_.bind();
  pipeline_.vertexBuffer().bindBase(GL_SHADER_STORAGE_BUFFER, 0);
  glBindBuffer(GL_DRAW_INDIRECT_BUFFER, pipeline_.counterBuffer().id());
  glDrawElementsIndirect(GL_TRIANGLES, GL_UNSIGNED_INT, nullptr);
  glBindBuffer(GL_DRAW_INDIRECT_BUFFER, 0);
  stats.triangles = pipeline_.indexCount() / 3;
  stats.vertices = pipeline_.vertexCount();
  stats.drawCalls = 1;
  return stats;
}

}  // namespace tellus
