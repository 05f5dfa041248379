#include "tellus/render/clipmaps/clipmap_renderer.hpp"

#include <chrono>
#include <cmath>

#include <glm/common.hpp>

#include <spdlog/spdlog.h>

#include <fmt/format.h>

#include "tellus/core/stopwatch.hpp"
#include "tellus/core/frustum.hpp"
#include "tellus/core/thread_cpu_clock.hpp"
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
  {
    // Each level's tile errors, for the screen-space error shading (a layer a level).
    const ClipmapStoreLevels::TileErrors finest = r->levels_->tileErrors(0);
    r->tileErrors_ = gl::Texture::create2DArray(GL_R32F, finest.tilesX, finest.tilesY, levels);
    r->tileErrors_.setFilter(GL_NEAREST, GL_NEAREST);
    for (int level = 0; level < levels; ++level) {
      ClipmapStoreLevels::TileErrors t = r->levels_->tileErrors(level);
      std::vector<float> layer(std::size_t(finest.tilesX) * std::size_t(finest.tilesY), 0.0f);
      for (int y = 0; y < t.tilesY; ++y) {
        std::copy_n(&t.errorM[std::size_t(y) * std::size_t(t.tilesX)], t.tilesX,
                    &layer[std::size_t(y) * std::size_t(finest.tilesX)]);
      }
      glTextureSubImage3D(r->tileErrors_.id(), 0, 0, 0, level, finest.tilesX, finest.tilesY, 1, GL_RED, GL_FLOAT,
                          layer.data());
      r->errorTiles_.emplace_back(t.tilesX, t.tilesY);
      r->errorSpanSamples_.push_back(float(t.spanSamples));
    }
  }
  Result<FillAndWirePrograms> programs = loadFillAndWirePrograms("clipmaps/clipmap.vert", "clipmaps/clipmap.frag");
  if (!programs) return programs.error();
  r->fill_ = std::move(programs->fill);
  r->wire_ = std::move(programs->wire);
  r->indexBuffer_ = gl::Buffer(r->footprints_.indices.size() * sizeof(std::uint32_t), r->footprints_.indices.data());
  r->vertexArray_ = gl::VertexArray::create();
  r->vertexArray_.setIndexBuffer(r->indexBuffer_);
  const int size = r->shape_.textureSize;
  for (HeightTexture& state : r->textures_) {
    state.heights = gl::Texture::create2DArray(GL_RG32F, size, size, levels);
    state.heights.setFilter(GL_LINEAR, GL_LINEAR);
    state.heights.setWrap(GL_REPEAT);  // toroidal: the texture wraps where the window does
  }
  Result<std::unique_ptr<ClipmapTexelStaging>> staging = ClipmapTexelStaging::create(r->shape_);
  if (!staging) return staging.error();
  r->staging_ = std::move(staging.value());
  r->staging_->prime(r->textures_[0].heights);
  return r;
}

ClipmapRenderer::~ClipmapRenderer() { finishUpdate(); }

clipmaps::ClipmapUpdate ClipmapRenderer::buildUpdate(const std::vector<glm::ivec2>* from,
                                                      glm::dvec2 viewer) {
  const clipmaps::LevelSampler stored = [this](int l, glm::ivec2 s) { return levels_->sample(l, s); };
  return clipmaps::buildClipmapUpdate(shape_, from, viewer, stored, levelFilter());
}

void ClipmapRenderer::upload(HeightTexture& texture, const clipmaps::ClipmapUpdate& update) {
  for (const clipmaps::TexelRect& rect : update.rects) {
    glTextureSubImage3D(texture.heights.id(), 0, rect.texel.x, rect.texel.y, rect.level, rect.size.x,
                        rect.size.y, 1, GL_RG, GL_FLOAT, rect.texels.data());
  }
  holdWindows(texture, update);
}

void ClipmapRenderer::holdWindows(HeightTexture& texture, const clipmaps::ClipmapUpdate& update) {
  texture.origins = update.origins;
  texture.viewer = update.viewer;
  texture.filled = true;
}

void ClipmapRenderer::startUpdate(int texture, glm::dvec2 viewer) {
  const HeightTexture& target = textures_[std::size_t(texture)];
  std::optional<std::vector<glm::ivec2>> from;
  if (target.filled) from = target.origins;
  updateTexture_ = texture;
  // The worker also stages the texels for the GPU's copy when a slot is free (else the render
  // thread uploads them itself when the update lands).
  updateSlot_ = staging_ ? staging_->acquire() : -1;
  // The worker is the only reader of levels_ while the job runs (the render thread reads them
  // only for the first fill, before any job), and the only writer of its staging slot.
  update_.start([this, from = std::move(from), viewer, slot = updateSlot_] {
    UpdateResult result;
    result.update = buildUpdate(from ? &*from : nullptr, viewer);
    result.error = levels_->firstError();
    result.staged = slot >= 0 && staging_->write(slot, result.update);
    return result;
  });
}

void ClipmapRenderer::releaseUpdateSlot() {
  if (updateSlot_ >= 0) staging_->release(updateSlot_);
  updateSlot_ = -1;
}

int ClipmapRenderer::landUpdate() {
  auto [result, workerMs] = update_.take();
  HeightTexture& target = textures_[std::size_t(updateTexture_)];
  ++workerUpdates_;
  if (result.staged) {
    ++stagedUpdates_;
    staging_->copy(updateSlot_, target.heights);  // releases the slot
    updateSlot_ = -1;
    holdWindows(target, result.update);
  } else {
    releaseUpdateSlot();
    upload(target, result.update);
  }
  lastUploadSamples_ += result.update.samples;
  unreportedWorkerCpuMs_ += workerMs;
  if (result.error && !dataError_) dataError_ = result.error;
  return updateTexture_;
}

bool ClipmapRenderer::farBehind(const std::vector<glm::ivec2>& wanted,
                                const std::vector<glm::ivec2>& held) const {
  // The finest window more than a block (m samples, a quarter of it) from where the viewer wants
  // it (a teleport, a path sampled sparsely, a turn the prediction missed): level borders would
  // come near the camera.
  if (held.empty()) return true;
  const glm::ivec2 lag = glm::abs(wanted.front() - held.front());
  return std::max(lag.x, lag.y) > shape_.m;
}

void ClipmapRenderer::finishUpdate() { update_.wait(); }

void ClipmapRenderer::cull(DrawnFrame& state, const ViewSetup& view, float exaggeration) const {
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
  // The levels centre on the terrain point nearest the eye: a viewer beyond the terrain's edge
  // (an orbit) still has the coarsest level over all of it, the finest where the terrain is
  // nearest.
  const glm::dvec2 viewer = glm::clamp(
      glm::dvec2(view.camera.position.x / spacingXM_, double(gridHeight_ - 1) - view.camera.position.y / spacingYM_),
      glm::dvec2(0.0), glm::dvec2(double(gridWidth_ - 1), double(gridHeight_ - 1)));
  previousFrame_ = frame_;
  lastUploadSamples_ = 0;
  int drawn = frame_.texture;
  if (drawn < 0) {
    // The first frame: filled here, on the render thread (nothing to draw meanwhile).
    const clipmaps::ClipmapUpdate update = buildUpdate(nullptr, viewer);
    upload(textures_[0], update);
    lastUploadSamples_ = update.samples;
    dataError_ = levels_->firstError();
    drawn = 0;
  } else if (update_.ready()) {
    // A ready update lands in the texture the last frame did not draw, and this frame draws it.
    drawn = landUpdate();
  }
  const std::vector<glm::ivec2> wanted = clipmaps::placeLevels(shape_, viewer);
  if (farBehind(wanted, textures_[std::size_t(drawn)].origins)) {
    // A jump (a teleport, a path sampled sparsely): the finest window would lag too far behind
    // the viewer for a frame or more. The update is made here, into the texture the last frame
    // did not draw (after the one in flight for it, if any, lands there).
    finishUpdate();
    const int other = 1 - drawn;
    if (update_.ready()) landUpdate();  // it was for `other` (this frame had not drawn it)
    update_.discard();                  // (a job that threw: nothing to land)
    releaseUpdateSlot();
    HeightTexture& target = textures_[std::size_t(other)];
    const clipmaps::ClipmapUpdate update = buildUpdate(target.filled ? &target.origins : nullptr, viewer);
    upload(target, update);
    lastUploadSamples_ += update.samples;
    if (!dataError_) dataError_ = levels_->firstError();
    drawn = other;
    ++jumps_;
  }
  const HeightTexture& texture = textures_[std::size_t(drawn)];
  frame_.texture = drawn;
  frame_.origins = texture.origins;
  // The geomorph follows the viewer while the windows are where it wants them; while an update
  // is on its way, it stays with the viewer the windows were placed for (each level's
  // transition band then still ends at its border).
  frame_.viewer = wanted == texture.origins ? viewer : texture.viewer;
  lastUpdateMs_ = start.elapsedMs();
  cull(frame_, view, settings.verticalExaggeration);
  // The update is placed for where the viewer will be when it lands (a frame on, at the same
  // velocity), so that the landed windows are centred on it rather than a frame behind.
  const glm::dvec2 predicted = glm::clamp(viewer + (hasLastViewer_ ? viewer - lastViewer_ : glm::dvec2(0.0)),
                                          glm::dvec2(0.0), glm::dvec2(double(gridWidth_ - 1), double(gridHeight_ - 1)));
  if (!update_.running() && clipmaps::placeLevels(shape_, predicted) != texture.origins) {
    startUpdate(1 - drawn, predicted);
  }
  lastViewer_ = viewer;
  hasLastViewer_ = true;
  ++prepared_;
  preparedThisFrame_ = true;
}

FrameStats ClipmapRenderer::draw(const ViewSetup& view, const RenderSettings& settings) {
  if (!preparedThisFrame_) prepare(view, settings);
  preparedThisFrame_ = false;
  drawFrame(frame_, view, settings);
  FrameStats stats;
  stats.triangles = frame_.triangles;
  stats.vertices = frame_.triangles * 3;
  stats.drawCalls = frame_.drawList.size();
  stats.textureUpdateMs = lastUpdateMs_;
  stats.uploadBytes = lastUploadSamples_ * sizeof(glm::vec2);
  stats.backgroundCpuMs = unreportedWorkerCpuMs_;
  unreportedWorkerCpuMs_ = 0.0;
  return stats;
}

bool ClipmapRenderer::drawPreviousSelection(const ViewSetup& view, const RenderSettings& settings) {
  if (prepared_ < 2) return false;
  drawFrame(previousFrame_, view, settings);
  return true;
}

void ClipmapRenderer::drawFrame(const DrawnFrame& state, const ViewSetup& view, const RenderSettings& settings) {
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
  textures_[std::size_t(state.texture)].heights.bindUnit(0);
  tileErrors_.bindUnit(2);
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
        const int coarser = std::min(level + 1, shape_.levels - 1);
        program.set("uErrorLayers", glm::ivec2(level, coarser));
        program.set("uErrorTiles", errorTiles_[std::size_t(level)]);
        program.set("uCoarserErrorTiles", errorTiles_[std::size_t(coarser)]);
        program.set("uErrorSpanSamples",
                    glm::vec2(errorSpanSamples_[std::size_t(level)], errorSpanSamples_[std::size_t(coarser)]));
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
  gl::readTextureSubImage(textures_[std::size_t(std::max(frame_.texture, 0))].heights.id(), 0, 0, 0, level, size, size, 1,
                          GL_RG, GL_FLOAT, out.size() * sizeof(glm::vec2), out.data());
  return out;
}

std::vector<std::string> ClipmapRenderer::frameReport() const {
  return {fmt::format("{} levels of {} x {} vertices", shape_.levels, options_.n, options_.n),
          fmt::format("texture update: {} samples, {:.2f} ms on this thread ({} made at once)",
                      countText(lastUploadSamples_), lastUpdateMs_, jumps_),
          fmt::format("worker updates {}, {} of them copied by the GPU from staging ({:.1f} MiB x {})",
                      workerUpdates_, stagedUpdates_, double(staging_->slotBytes()) / double(1 << 20),
                      ClipmapTexelStaging::kSlots)};
}

}  // namespace tellus
