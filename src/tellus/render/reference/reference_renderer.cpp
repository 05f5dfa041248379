#include "tellus/render/reference/reference_renderer.hpp"

#include <algorithm>
#include <cmath>

#include "tellus/core/progress.hpp"
#include "tellus/gl/gpu_wait.hpp"
#include "tellus/render/drawing/wireframe_overlay.hpp"

namespace tellus {
namespace {

// Chunk heights with a one-sample apron, clamped at the grid's borders.
std::vector<float> chunkHeightsWithApron(const HeightGrid& grid, int firstCol, int firstRow,
                                         int vertsX, int vertsY) {
  const int w = vertsX + 2, h = vertsY + 2;
  std::vector<float> out(size_t(w) * size_t(h));
  for (int y = 0; y < h; ++y) {
    const int row = std::clamp(firstRow + y - 1, 0, grid.height - 1);
    for (int x = 0; x < w; ++x) {
      const int col = std::clamp(firstCol + x - 1, 0, grid.width - 1);
      out[size_t(y) * size_t(w) + size_t(x)] = grid.at(col, row);
    }
  }
  return out;
}

}  // namespace

Result<ReferenceRenderer> ReferenceRenderer::create(const HeightGrid& grid) {
  if (grid.width < 2 || grid.height < 2) return makeError("cannot render a grid smaller than 2x2");
  ReferenceRenderer renderer;
  Result<FillAndWirePrograms> programs =
      loadFillAndWirePrograms("terrain/reference.vert", "terrain/terrain.frag");
  if (!programs) return programs.error();
  renderer.fill_ = std::move(programs->fill);
  renderer.wire_ = std::move(programs->wire);
  renderer.vertexArray_ = gl::VertexArray::create();
  renderer.spacingXM_ = grid.spacingXM;
  renderer.spacingYM_ = grid.spacingYM;
  renderer.gridHeight_ = grid.height;

  const int chunksX = (grid.width - 2) / kChunkQuads + 1;
  const int chunksY = (grid.height - 2) / kChunkQuads + 1;
  Progress progress("upload", std::uint64_t(chunksX) * std::uint64_t(chunksY));
  for (int cy = 0; cy < chunksY; ++cy) {
    for (int cx = 0; cx < chunksX; ++cx) {
      Chunk chunk;
      chunk.firstCol = cx * kChunkQuads;
      chunk.firstRow = cy * kChunkQuads;
      chunk.vertsX = std::min(kChunkQuads, grid.width - 1 - chunk.firstCol) + 1;
      chunk.vertsY = std::min(kChunkQuads, grid.height - 1 - chunk.firstRow) + 1;
      const std::vector<float> heights =
          chunkHeightsWithApron(grid, chunk.firstCol, chunk.firstRow, chunk.vertsX, chunk.vertsY);
      chunk.heights = gl::Texture::create2D(GL_R32F, chunk.vertsX + 2, chunk.vertsY + 2);
      chunk.heights.upload2D(0, 0, 0, chunk.vertsX + 2, chunk.vertsY + 2, GL_RED, GL_FLOAT,
                             heights.data());
      chunk.heights.setFilter(GL_LINEAR, GL_LINEAR);
      chunk.heights.setWrap(GL_CLAMP_TO_EDGE);
      chunk.indices = &renderer.indexBuffers_.forGrid(chunk.vertsX, chunk.vertsY);
      renderer.chunks_.push_back(std::move(chunk));
      progress.advance();
    }
  }
  return renderer;
}

void ReferenceRenderer::drawChunks(const gl::Program& program, const ViewSetup& view,
                                   FrameStats* stats, Progress* progress) {
  program.use();
  program.set("uViewProjection", glm::mat4(view.relativeViewProjection()));
  program.set("uSpacing", glm::vec2(float(spacingXM_), float(spacingYM_)));
  program.set("uExaggeration", exaggeration_);
  vertexArray_.bind();
  for (const Chunk& chunk : chunks_) {
    // Chunk origin relative to the camera, computed in double precision.
    const glm::dvec3 origin(chunk.firstCol * spacingXM_,
                            (gridHeight_ - 1 - chunk.firstRow) * spacingYM_, 0.0);
    program.set("uChunkOrigin", glm::vec3(origin - view.camera.position));
    program.set("uChunkVertsX", chunk.vertsX);
    chunk.heights.bindUnit(0);
    vertexArray_.setIndexBuffer(*chunk.indices);
    const auto indexCount = GLsizei(chunk.indices->size() / sizeof(std::uint32_t));
    glDrawElements(GL_TRIANGLES, indexCount, GL_UNSIGNED_INT, nullptr);
    if (progress && progress->active()) {
      if (++drawnSinceFinish_ % 8 == 0) gl::finish();  // let the display follow the GPU
      progress->advance();
    }
    if (stats) {
      stats->triangles += std::uint64_t(indexCount / 3);
      stats->vertices += std::uint64_t(chunk.vertsX) * std::uint64_t(chunk.vertsY);
      ++stats->drawCalls;
    }
  }
}

FrameStats ReferenceRenderer::draw(const ViewSetup& view, const RenderSettings& settings,
                                   Progress* progress) {
  exaggeration_ = settings.verticalExaggeration;
  applyShadingMode(fill_, view, settings);
  FrameStats stats;
  drawWithWireframeOverlay(
      settings.wireframe, wire_, view, [&] { drawChunks(fill_, view, &stats, progress); },
      [&] { drawChunks(wire_, view, nullptr, progress); });
  return stats;
}

}  // namespace tellus
