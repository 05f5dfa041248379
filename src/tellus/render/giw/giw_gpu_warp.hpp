#pragma once
// Geometry image warping's per-frame work on the GPU (Dachsbacher & Stamminger 2004 compute the
// importance and the warp on the GPU): two compute passes (shaders/giw/) following the CPU
// reference (lod/giw/giw_warp.hpp: importanceMap, warpRowsThenColumns, buildGeometryImage) step
// for step. The first, a work group a sketch row, computes the row's importance and warps it to
// equal shares; the last row's group to finish then makes the one distribution of all columns.
// The second resamples the warped vertices from the grid's height texture, straight into the
// vertex buffer the frame draws. The CPU only places the sketch region (four rays) and issues
// the two dispatches (each a fixed cost on the render thread, hence two, not four). Needs a
// current GL 4.5 context.
#include <glm/vec2.hpp>

#include "tellus/core/result.hpp"
#include "tellus/dem/height_grid.hpp"
#include "tellus/gl/buffer.hpp"
#include "tellus/gl/program.hpp"
#include "tellus/gl/texture.hpp"
#include "tellus/lod/giw/giw_warp.hpp"
#include "tellus/lod/lod_view.hpp"

namespace tellus {

class GiwGpuWarp {
 public:
  // Programs and scratch buffers for geometry images of `size` x `size` vertices.
  static Result<GiwGpuWarp> create(int size);

  // The warped geometry image of `region` for `view` into `vertices` (size^2 vec4: x, y in grid
  // units, height in metres, LOD level), from `heights` (the whole grid, R32F, row 0 north).
  void run(const gl::Texture& heights, const HeightGrid& grid, const giw::Region& region,
           const LodView& view, const giw::GiwSettings& settings, const gl::Buffer& vertices);

 private:
  // The uniforms set only when they change, as last set.
  struct Constants {
    glm::vec2 spacing{0.0f};
    float slopeWeight = 0.0f, outsideImportance = 0.0f, uniformShare = 0.0f;
    bool operator==(const Constants&) const = default;
  };

  int size_ = 0;
  Constants constants_;
  bool constantsSet_ = false;
  gl::Program rows_, resample_;
  gl::Buffer importanceMap_, rowX_, rowTotals_, cumulative_, columnT_;
  gl::Buffer rowsDone_;  // one uint: rows finished in the running pass, 0 between passes
};

}  // namespace tellus
