#include "tellus/render/clipmaps/clipmap_renderer.hpp"

#include <chrono>
#include <cmath>

#include <glm/common.hpp>

#include <spdlog/spdlog.h>

#include <fmt/format.h>

#include "tellus/core/stopwatch.hpp"
#include "tellus/core/frustum.hpp"
#include "tellus/gl/gpu_wait.hpp"
#include "tellus/lod/clipmaps/clipmap_heights.hpp"
#include "tellus/render/drawing/wireframe_overlay.hpp"

namespace tellus {

using clipmaps::ClipmapShape;
using clipmaps::Piece;
using clipmaps::SampleRect;

Result<std::unique_ptr<ClipmapRenderer>> ClipmapRenderer::create(std::shared_ptr<const TileStore> store,
                                                                 const ClipmapOptions& options) {
  const PyramidLayout& layout = store->layout();
  const int levels = options.levels > 0
                         ? options.levels
                         : ClipmapShape::levelsFor(options.n, layout.dataWidth(), layout.dataHeight());
  Result<ClipmapShape> shape = ClipmapShape::create(options.n, levels);
  if (!shape) return shape.error();
  if (options.transitionWidth > 0.0f) {
    if (options.transitionWidth > shape->maxTransitionWidth()) {
      return makeError("clipmap transition width {} is wider than the {} units a level of {} vertices allows",
                       options.transitionWidth, shape->maxTransitionWidth(), shape->n);
    }
    shape->transitionWidth = options.transitionWidth;
  }
  std::unique_ptr<ClipmapRenderer> r(new ClipmapRenderer());
  r->options_ = options;
  r->store_ = store;
  r->shape_ = shape.value();
  r->footprints_ = clipmaps::buildFootprints(r->shape_);
  r->levels_ = std::make_unique<ClipmapStoreLevels>(store, options.cacheBytes);
  r->gridWidth_ = layout.dataWidth();
  r->gridHeight_ = layout.dataHeight();
  r->spacingXM_ = store->metadata().spacingXM;
  r->spacingYM_ = store->metadata().spacingYM;
  r->minHeightM_ = store->metadata().minHeightM;
  r->maxHeightM_ = store->metadata().maxHeightM;
  for (int level = 0; level < levels; ++level) r->levelErrorM_.push_back(r->levels_->geometricErrorM(level));
  Result<FillAndWirePrograms> programs = loadFillAndWirePrograms("clipmaps/clipmap.vert", "clipmaps/clipmap.frag");
  if (!programs) return programs.error();
  r->fill_ = std::move(programs->fill);
  r->wire_ = std::move(programs->wire);
  r->indexBuffer_ = gl::Buffer(r->footprints_.indices.size() * sizeof(std::uint32_t), r->footprints_.indices.data());
  r->vertexArray_ = gl::VertexArray::create();
  r->vertexArray_.setIndexBuffer(r->indexBuffer_);
  const int size = r->shape_.textureSize;
  for (FrameState& state : r->frames_) {
    state.heights = gl::Texture::create2DArray(GL_RG32F, size, size, levels);
    state.heights.setFilter(GL_LINEAR, GL_LINEAR);
    state.heights.setWrap(GL_REPEAT);  // toroidal: the texture wraps where the window does
  }
  return r;
}

void ClipmapRenderer::uploadRect(FrameState& state, int level, const SampleRect& rect) {
  const clipmaps::LevelSampler sampler = [this](int l, glm::ivec2 s) { return levels_->sample(l, s); };
  for (const clipmaps::ToroidalPiece& piece : clipmaps::wrapToroidally(rect, shape_.textureSize)) {
    const glm::ivec2 size = piece.samples.max - piece.samples.min;
    staging_.resize(std::size_t(size.x) * std::size_t(size.y));
    std::size_t i = 0;
    for (int y = piece.samples.min.y; y < piece.samples.max.y; ++y) {
      for (int x = piece.samples.min.x; x < piece.samples.max.x; ++x) {
        staging_[i++] = clipmaps::texelHeights(sampler, shape_, level, {x, y});
      }
    }
    glTextureSubImage3D(state.heights.id(), 0, piece.texel.x, piece.texel.y, level, size.x, size.y, 1,
                        GL_RG, GL_FLOAT, staging_.data());
  }
}

std::uint64_t ClipmapRenderer::updateTexture(FrameState& state, const std::vector<glm::ivec2>& origins) {
  std::uint64_t samples = 0;
  for (int level = 0; level < shape_.levels; ++level) {
    const glm::ivec2 to = origins[std::size_t(level)];
    const std::vector<SampleRect> regions =
        state.filled ? clipmaps::exposedRegions(shape_, state.origins[std::size_t(level)], to)
                     : std::vector<SampleRect>{SampleRect{to, to + shape_.n}};
    for (const SampleRect& rect : regions) {
      uploadRect(state, level, rect);
      const glm::ivec2 size = rect.max - rect.min;
      samples += std::uint64_t(size.x) * std::uint64_t(size.y);
    }
  }
  state.origins = origins;
  state.filled = true;
  return samples;
}

void ClipmapRenderer::cull(FrameState& state, const ViewSetup& view, float exaggeration) const {
  state.drawList.clear();
  state.triangles = 0;
  const Frustum frustum = Frustum::fromMatrix(view.relativeViewProjection());
  for (int level = 0; level < shape_.levels; ++level) {
    const glm::ivec2 origin = state.origins[std::size_t(level)];
    const glm::ivec2 trim =
        level > 0 ? clipmaps::trimSide(shape_, origin, state.origins[std::size_t(level - 1)]) : glm::ivec2(0);
    const int scale = 1 << level;
    for (const Piece* piece : clipmaps::piecesForLevel(footprints_, shape_, level, trim)) {
      // The piece's full-resolution samples (col, row), then its world box.
      const glm::dvec2 lo = glm::dvec2((origin + piece->min) * scale);
      const glm::dvec2 hi = glm::dvec2((origin + piece->max) * scale);
      if (hi.x < 0.0 || hi.y < 0.0 || lo.x > gridWidth_ - 1 || lo.y > gridHeight_ - 1) continue;
      if (options_.culling) {
        Aabb box;
        box.min = {lo.x * spacingXM_, (gridHeight_ - 1 - hi.y) * spacingYM_, double(minHeightM_) * exaggeration};
        box.max = {hi.x * spacingXM_, (gridHeight_ - 1 - lo.y) * spacingYM_, double(maxHeightM_) * exaggeration};
        box.min -= view.camera.position;
        box.max -= view.camera.position;
        if (!frustum.intersects(box)) continue;
      }
      state.drawList.emplace_back(level, piece);
      state.triangles += piece->indexCount / 3;
    }
  }
}

void ClipmapRenderer::prepare(const ViewSetup& view, const RenderSettings& settings) {
  const Stopwatch start;
  current_ = 1 - current_;
  FrameState& state = frames_[std::size_t(current_)];
  // The levels centre on the terrain point nearest the eye: a viewer beyond the terrain's edge
  // (an orbit) still has the coarsest level over all of it, the finest where the terrain is
  // nearest.
  state.viewer = glm::clamp(glm::dvec2(view.camera.position.x / spacingXM_,
                                       double(gridHeight_ - 1) - view.camera.position.y / spacingYM_),
                            glm::dvec2(0.0), glm::dvec2(double(gridWidth_ - 1), double(gridHeight_ - 1)));
  lastUploadSamples_ = updateTexture(state, clipmaps::placeLevels(shape_, state.viewer));
  lastUpdateMs_ = start.elapsedMs();
  cull(state, view, settings.verticalExaggeration);
  ++prepared_;
  preparedThisFrame_ = true;
}

FrameStats ClipmapRenderer::draw(const ViewSetup& view, const RenderSettings& settings) {
  if (!preparedThisFrame_) prepare(view, settings);
  preparedThisFrame_ = false;
  const FrameState& state = frames_[std::size_t(current_)];
  drawFrame(state, view, settings);
  FrameStats stats;
  stats.triangles = state.triangles;
  stats.vertices = state.triangles * 3;
  stats.drawCalls = state.drawList.size();
  stats.textureUpdateMs = lastUpdateMs_;
  stats.uploadBytes = lastUploadSamples_ * sizeof(glm::vec2);
  return stats;
}

bool ClipmapRenderer::drawPreviousSelection(const ViewSetup& view, const RenderSettings& settings) {
  if (prepared_ < 2) return false;
  drawFrame(frames_[std::size_t(1 - current_)], view, settings);
  return true;
}

void ClipmapRenderer::drawFrame(const FrameState& state, const ViewSetup& view, const RenderSettings& settings) {
  const double cameraCol = view.camera.position.x / spacingXM_;
  const double cameraRow = double(gridHeight_ - 1) - view.camera.position.y / spacingYM_;
  for (const gl::Program* program : {&fill_, &wire_}) {
    program->set("uClipFromRelative", glm::mat4(view.relativeViewProjection()));
    program->set("uN", shape_.n);
    program->set("uTextureSize", shape_.textureSize);
    program->set("uSpacing", glm::vec2(float(spacingXM_), float(spacingYM_)));
    program->set("uExaggeration", settings.verticalExaggeration);
    program->set("uCameraZ", float(view.camera.position.z));
    program->set("uBlendStart", shape_.blendStart());
    program->set("uBlendWidth", shape_.transitionWidth);
    program->set("uCameraSample", glm::vec2(float(cameraCol), float(cameraRow)));
    program->set("uGridMax", glm::vec2(float(gridWidth_ - 1), float(gridHeight_ - 1)));
  }
  applyShadingMode(fill_, view, settings);
  state.heights.bindUnit(0);
  const auto drawWith = [&](const gl::Program& program) {
    program.use();
    vertexArray_.bind();
    int boundLevel = -1;
    for (const auto& [level, piece] : state.drawList) {
      if (level != boundLevel) {
        const glm::ivec2 origin = state.origins[std::size_t(level)];
        const double scale = std::ldexp(1.0, level);
        program.set("uLevel", level);
        program.set("uHasCoarser", level + 1 < shape_.levels ? 1 : 0);
        program.set("uOrigin", origin);
        program.set("uScale", float(scale));
        program.set("uViewerLocal", glm::vec2(state.viewer / scale - glm::dvec2(origin)));
        const float coarserError = levelErrorM_[std::size_t(std::min(level + 1, shape_.levels - 1))];
        program.set("uLevelErrorM", glm::vec2(levelErrorM_[std::size_t(level)], coarserError));
        boundLevel = level;
      }
      glDrawElements(GL_TRIANGLES, GLsizei(piece->indexCount), GL_UNSIGNED_INT,
                     reinterpret_cast<const void*>(std::uintptr_t(piece->firstIndex) * sizeof(std::uint32_t)));
    }
  };
  drawWithWireframeOverlay(settings.wireframe, wire_, view, [&] { drawWith(fill_); }, [&] { drawWith(wire_); });
}

std::vector<glm::vec2> ClipmapRenderer::readLevel(int level) const {
  const int size = shape_.textureSize;
  std::vector<glm::vec2> out(std::size_t(size) * std::size_t(size));
  gl::readTextureSubImage(frames_[std::size_t(current_)].heights.id(), 0, 0, 0, level, size, size, 1,
                          GL_RG, GL_FLOAT, out.size() * sizeof(glm::vec2), out.data());
  return out;
}

std::vector<std::string> ClipmapRenderer::frameReport() const {
  return {fmt::format("{} levels of {} x {} vertices", shape_.levels, options_.n, options_.n),
          fmt::format("texture update: {} samples, {:.2f} ms", countText(lastUploadSamples_),
                      lastUpdateMs_)};
}

}  // namespace tellus
