#pragma once
// The brute-force reference renderer: every height sample is a vertex, every grid cell two
// triangles, no LOD and no culling. It is the ground truth the LOD renderers are measured
// against. The grid is cut into chunks of kChunkQuads x kChunkQuads cells, each a height
// texture with a one-sample apron (so per-pixel normals are continuous across chunks); the
// mesh is pulled from the texture by gl_VertexID, so a 4801 x 4801 grid costs ~100 MB of GPU
// memory. Positions reach the GPU camera-relative (double on the CPU), so there is no jitter
// far from the origin. Needs a current GL 4.5 context for its whole life.
#include <cstdint>
#include <vector>

#include "tellus/core/camera.hpp"
#include "tellus/core/progress.hpp"
#include "tellus/dem/height_grid.hpp"
#include "tellus/gl/buffer.hpp"
#include "tellus/gl/program.hpp"
#include "tellus/gl/texture.hpp"
#include "tellus/gl/vertex_array.hpp"
#include "tellus/render/drawing/grid_index_buffers.hpp"
#include "tellus/render/terrain_renderer.hpp"
#include "tellus/render/shading/terrain_shading.hpp"

namespace tellus {

class ReferenceRenderer final : public TerrainRenderer {
 public:
  static constexpr int kChunkQuads = 256;

  // Uploads the grid. Errors: shaders that do not compile, a grid smaller than 2x2.
  static Result<ReferenceRenderer> create(const HeightGrid& grid);

  std::string_view name() const override { return "reference"; }

  // Draws into the bound framebuffer (depth state as set by OffscreenTarget::begin()).
  FrameStats draw(const ViewSetup& view, const RenderSettings& settings) override {
    return draw(view, settings, nullptr);
  }
  // The same with a progress display: with an active `progress` (one step per chunk and pass),
  // the GPU is waited for every few chunks so the display follows the real work; never use it
  // when timing frames.
  FrameStats draw(const ViewSetup& view, const RenderSettings& settings, Progress* progress);

  // Chunks drawn per pass (a wireframe frame makes two passes).
  std::size_t chunkCount() const { return chunks_.size(); }

 private:
  struct Chunk {
    int firstCol = 0, firstRow = 0;  // grid sample of the chunk's vertex (0, 0)
    int vertsX = 0, vertsY = 0;
    gl::Texture heights;                  // (vertsX + 2) x (vertsY + 2), R32F metres
    const gl::Buffer* indices = nullptr;  // shared by all chunks of this size (owned below)
  };

  void drawChunks(const gl::Program& program, const ViewSetup& view, FrameStats* stats,
                  Progress* progress);

  std::vector<Chunk> chunks_;
  GridIndexBuffers indexBuffers_;  // chunks point into it
  gl::Program fill_, wire_;
  gl::VertexArray vertexArray_;
  double spacingXM_ = 1.0, spacingYM_ = 1.0;
  int gridHeight_ = 0;
  float exaggeration_ = 1.0f;
  std::uint64_t drawnSinceFinish_ = 0;
};

}  // namespace tellus
