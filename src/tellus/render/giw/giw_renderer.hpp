#pragma once
// Geometry image warping (seed 004 section 2.4; Dachsbacher & Stamminger 2004) on a height
// grid: the warped geometry image of lod/giw/ built each frame in prepare() on the GPU, as the
// paper does (GiwGpuWarp: importance, row-then-column warp and resampled heights in compute
// passes, written straight into the frame's vertex buffer; the CPU places the sketch region),
// and drawn as a quad mesh from a fixed index buffer. A grid beyond one texture (its shading
// texture is a coarser level) is warped on the CPU instead (lod/giw/, the reference) and its
// geometry image uploaded. The paper's procedural detail is not added: Tellus draws the measured
// terrain, so its error is the warp's own. Needs a current GL 4.5 context.
#include <array>
#include <memory>
#include <string>

#include "tellus/core/result.hpp"
#include "tellus/dem/height_grid.hpp"
#include "tellus/gl/buffer.hpp"
#include "tellus/gl/program.hpp"
#include "tellus/gl/texture.hpp"
#include "tellus/gl/vertex_array.hpp"
#include "tellus/lod/giw/giw_warp.hpp"
#include "tellus/render/drawing/grid_mesh_shading.hpp"
#include "tellus/render/giw/giw_gpu_warp.hpp"
#include "tellus/render/terrain_renderer.hpp"

namespace tellus {

struct GiwOptions {
  std::string name = "giw";
  giw::GiwSettings settings;
};

class GiwRenderer final : public TerrainRenderer {
 public:
  // `grid` must outlive the renderer. Errors: settings out of range, shaders.
  static Result<std::unique_ptr<GiwRenderer>> create(const HeightGrid& grid, const GiwOptions& options);

  std::string_view name() const override { return options_.name; }
  void prepare(const ViewSetup& view, const RenderSettings& settings) override;
  FrameStats draw(const ViewSetup& view, const RenderSettings& settings) override;
  bool drawPreviousSelection(const ViewSetup& view, const RenderSettings& settings) override;
  std::vector<std::string> frameReport() const override;

  // The geometry image the last draw() drew (read back from the GPU: waits; tests). Its
  // density is not kept (the vertices carry the tint's level).
  giw::GeometryImage readImage() const;
  // The warp runs on the GPU (else on the CPU: a grid beyond one texture).
  bool warpsOnGpu() const { return gpu_ != nullptr; }
  void setSlopeWeight(float weight) { options_.settings.slopeWeight = weight; }

 private:
  GiwRenderer() = default;
  void drawImage(int which, const ViewSetup& view, const RenderSettings& settings);

  GiwOptions options_;
  const HeightGrid* grid_ = nullptr;
  float lowestM_ = 0.0f;  // the grid's lowest height, metres
  bool prepared_ = false;
  std::unique_ptr<GiwGpuWarp> gpu_;
  std::array<giw::Region, 2> regions_;        // of each vertex buffer's image
  std::array<giw::GeometryImage, 2> images_;  // the CPU path's images
  std::array<gl::Buffer, 2> vertices_;
  std::array<gl::VertexArray, 2> arrays_;
  gl::Buffer indices_;
  GLsizei indexCount_ = 0;
  int current_ = 0;
  int framesDrawn_ = 0;
  std::size_t uploadBytes_ = 0;  // the CPU path's geometry image a frame
  GridMeshShading shading_;
};

}  // namespace tellus
