#pragma once
// Draws a terrain given as an explicit indexed triangle mesh: the output of CPU LOD algorithms
// (the classic baselines) and meshes built by tests (e.g. one with T-junctions, to prove the
// crack detector works). Vertex positions are floats relative to a double-precision origin,
// so there is no jitter far from the world origin. Needs a current GL 4.5 context.
#include <cstdint>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

#include "tellus/core/result.hpp"
#include "tellus/gl/buffer.hpp"
#include "tellus/gl/program.hpp"
#include "tellus/gl/vertex_array.hpp"
#include "tellus/render/terrain_renderer.hpp"

namespace tellus {

struct TriangleMesh {
  glm::dvec3 origin{0.0};              // world position the vertices are relative to
  std::vector<glm::vec3> positions;    // metres from origin; z is the height
  std::vector<std::uint32_t> indices;  // three per triangle
};

class MeshRenderer final : public TerrainRenderer {
 public:
  static Result<MeshRenderer> create(std::string name);

  std::string_view name() const override { return name_; }
  // Replaces the mesh (e.g. once per frame for a CPU LOD algorithm).
  Status upload(const TriangleMesh& mesh);
  FrameStats draw(const ViewSetup& view, const RenderSettings& settings) override;

 private:
  std::string name_;
  gl::Program program_;
  gl::VertexArray vertexArray_;
  gl::Buffer vertices_, indices_;
  glm::dvec3 origin_{0.0};
  std::uint64_t vertexCount_ = 0, indexCount_ = 0;
};

}  // namespace tellus
