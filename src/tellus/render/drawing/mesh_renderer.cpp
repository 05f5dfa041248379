#include "tellus/render/drawing/mesh_renderer.hpp"

#include <glm/gtc/type_ptr.hpp>

namespace tellus {

Result<MeshRenderer> MeshRenderer::create(std::string name) {
  MeshRenderer renderer;
  renderer.name_ = std::move(name);
  Result<gl::Program> program = gl::Program::fromFiles(
      {{GL_VERTEX_SHADER, "terrain/mesh.vert"}, {GL_FRAGMENT_SHADER, "terrain/mesh.frag"}});
  if (!program) return program.error();
  renderer.program_ = std::move(program.value());
  renderer.vertexArray_ = gl::VertexArray::create();
  return renderer;
}

Status MeshRenderer::upload(const TriangleMesh& mesh) {
  if (mesh.indices.size() % 3 != 0) return makeError("mesh index count is not a multiple of 3");
  for (std::uint32_t i : mesh.indices) {
    if (i >= mesh.positions.size()) return makeError("mesh index {} out of range", i);
  }
  origin_ = mesh.origin;
  vertexCount_ = mesh.positions.size();
  indexCount_ = mesh.indices.size();
  if (mesh.positions.empty() || mesh.indices.empty()) return {};
  vertices_ = gl::Buffer(mesh.positions.size() * sizeof(glm::vec3), mesh.positions.data());
  indices_ = gl::Buffer(mesh.indices.size() * sizeof(std::uint32_t), mesh.indices.data());
  vertexArray_.setVec3Positions(vertices_);
  vertexArray_.setIndexBuffer(indices_);
  return {};
}

FrameStats MeshRenderer::draw(const ViewSetup& view, const RenderSettings& settings) {
  FrameStats stats;
  if (indexCount_ == 0) return stats;
  applyShading(program_, settings.shading);
  program_.set("uViewProjection", glm::mat4(view.relativeViewProjection()));
  program_.set("uMeshOrigin", glm::vec3(origin_ - view.camera.position));
  program_.set("uExaggeration", settings.verticalExaggeration);
  program_.use();
  vertexArray_.bind();
  glDrawElements(GL_TRIANGLES, GLsizei(indexCount_), GL_UNSIGNED_INT, nullptr);
  stats.triangles = indexCount_ / 3;
  stats.vertices = vertexCount_;
  stats.drawCalls = 1;
  return stats;
}

}  // namespace tellus
