#pragma once
// GAMeR (seed 004 section 2.5; Boubekeur & Schlick 2005) on a height grid: the pattern pool of
// lod/gamer/ in one vertex buffer (the barycentric lattice) and one index buffer (every
// pattern's triangles), the coarse triangles' depth tags and patterns chosen on the GPU in
// prepare() (GamerGpuSelection: compute passes, the paper's GPU classification; the CPU
// reference is lod/gamer/gamer_refinement.hpp), and one glMultiDrawElementsIndirect a frame in
// draw(): a command per pattern, instanced over the coarse triangles that use it (instance
// attribute: cell, half). Nothing is read back: the triangle counts of a frame arrive a frame or
// more later (finishStats() waits for them). The vertex shader places each pattern vertex on
// its coarse triangle and reads its height from the grid texture. Needs a current GL 4.5
// context for its whole life.
#include <array>
#include <memory>
#include <string>
#include <vector>

#include "tellus/core/result.hpp"
#include "tellus/dem/height_grid.hpp"
#include "tellus/gl/buffer.hpp"
#include "tellus/gl/program.hpp"
#include "tellus/gl/texture.hpp"
#include "tellus/gl/vertex_array.hpp"
#include "tellus/lod/gamer/gamer_refinement.hpp"
#include "tellus/render/drawing/grid_mesh_shading.hpp"
#include "tellus/render/gamer/gamer_gpu_selection.hpp"
#include "tellus/render/terrain_renderer.hpp"

namespace tellus {

struct GamerOptions {
  std::string name = "gamer";
  gamer::GamerSettings settings;
};

class GamerRenderer final : public TerrainRenderer {
 public:
  // `grid` must outlive the renderer. Errors: settings out of range, a grid larger than one
  // texture (GAMeR reads its geometry from the grid texture), shaders that do not build.
  static Result<std::unique_ptr<GamerRenderer>> create(const HeightGrid& grid, const GamerOptions& options);

  std::string_view name() const override { return options_.name; }
  void prepare(const ViewSetup& view, const RenderSettings& settings) override;
  FrameStats draw(const ViewSetup& view, const RenderSettings& settings) override;
  // The last draw()'s triangle counts, waiting for the GPU's totals.
  void finishStats(FrameStats& stats) override;
  bool drawPreviousSelection(const ViewSetup& view, const RenderSettings& settings) override;
  std::vector<std::string> frameReport() const override;

  const gamer::PatternPool& pool() const { return pool_; }
  const gamer::CoarseTerrain& terrain() const { return terrain_; }
  // The last draw()'s selection, read back from the GPU (tests: waits; the CPU reference
  // expands it).
  gamer::Selection readSelection() const { return selection_->readSelection(frames_[std::size_t(current_)].output); }
  // Changes the error target (the viewer's panel).
  void setTargetPx(float targetPx) { options_.settings.targetPx = targetPx; }
  // Changes the geomorph band (the viewer's panel), 0 to 1.
  void setMorphBand(float band) { options_.settings.morphBand = band; }

 private:
  struct Frame {  // one frame's instances and draw commands on the GPU
    GamerGpuSelection::Output output;
    gl::VertexArray array;
  };

  GamerRenderer() = default;
  void drawFrame(const Frame& frame, const ViewSetup& view, const RenderSettings& settings);

  GamerOptions options_;
  gamer::PatternPool pool_;
  gamer::CoarseTerrain terrain_;
  std::unique_ptr<GamerGpuSelection> selection_;
  GamerGpuSelection::Totals lastTotals_;  // of the newest frame whose totals came back
  bool prepared_ = false;
  double runThreadMs_ = 0.0;  // the render thread's CPU in the last classification's dispatches
  std::array<Frame, 2> frames_;
  int current_ = 0;
  int framesDrawn_ = 0;
  gl::Buffer lattice_, patternIndices_;
  GridMeshShading shading_;  // its height texture is also the geometry's
};

}  // namespace tellus
