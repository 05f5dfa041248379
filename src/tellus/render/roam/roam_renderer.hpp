#pragma once
// ROAM (seed 004 section 2.1; Duchaineau et al. 1997): the CPU bintree of lod/roam/ refined for
// the view in prepare() (re-prioritise, split and merge; the harness's "CPU LOD ms"), its
// visible leaves streamed to the GPU in draw() as one vertex buffer of (u, v, height) triangles
// (the harness's "submit"). Shading reads a height texture for normals and tints, like RAG's:
// the grid itself, or its finest pyramid level that fits one texture (geometry always comes from
// the full grid). Needs a current GL 4.5 context for its whole life.
#include <array>
#include <memory>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

#include "tellus/core/result.hpp"
#include "tellus/dem/height_grid.hpp"
#include "tellus/gl/buffer.hpp"
#include "tellus/gl/program.hpp"
#include "tellus/gl/texture.hpp"
#include "tellus/gl/vertex_array.hpp"
#include "tellus/lod/roam/roam_mesh.hpp"
#include "tellus/render/drawing/grid_mesh_shading.hpp"
#include "tellus/render/terrain_renderer.hpp"

namespace tellus {

struct RoamOptions {
  std::string name = "roam";
  roam::RoamSettings settings;
};

class RoamRenderer final : public TerrainRenderer {
 public:
  // `grid` must outlive the renderer. Errors: settings out of range, shaders that do not build.
  static Result<std::unique_ptr<RoamRenderer>> create(const HeightGrid& grid, const RoamOptions& options);

  std::string_view name() const override { return options_.name; }
  void prepare(const ViewSetup& view, const RenderSettings& settings) override;
  FrameStats draw(const ViewSetup& view, const RenderSettings& settings) override;
  // Draws the previous frame's leaves (kept in the other vertex buffer) from `view`.
  bool drawPreviousSelection(const ViewSetup& view, const RenderSettings& settings) override;
  std::vector<std::string> frameReport() const override;

  const roam::RoamMesh& mesh() const { return *mesh_; }
  roam::RoamMesh& mesh() { return *mesh_; }
  const roam::RoamFrameReport& lastReport() const { return report_; }

 private:
  struct Streamed {  // one frame's triangles on the GPU
    gl::Buffer buffer;
    gl::VertexArray array;
    std::size_t capacityBytes = 0;
    std::uint64_t triangles = 0;
  };

  RoamRenderer() = default;
  void drawStreamed(const Streamed& streamed, const ViewSetup& view, const RenderSettings& settings);

  RoamOptions options_;
  std::unique_ptr<roam::RoamMesh> mesh_;
  roam::RoamFrameReport report_;
  bool prepared_ = false;
  std::array<Streamed, 2> streamed_;
  int current_ = 0;  // streamed_[current_] holds the last draw()'s triangles
  int framesDrawn_ = 0;
  GridMeshShading shading_;
};

}  // namespace tellus
