#include "tellus/render/rag/rag_renderer.hpp"

#include <algorithm>
#include <bit>
#include <cmath>

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include "tellus/render/drawing/wireframe_overlay.hpp"

namespace tellus {
namespace {

constexpr std::size_t kTriangleBytes = sizeof(rag::Triangle);
constexpr std::uint64_t kMinCapacity = 1u << 16;  // triangles

Status checkOptions(const RagOptions& options) {
  const rag::RefinementSettings& r = options.refinement;
  if (options.passes < 0 || options.passes > kRagMaxPasses) {
    return makeError("RAG: {} passes is outside 0 to {}", options.passes, kRagMaxPasses);
  }
  if (!(r.pixelEdge > 0.0f) || !std::isfinite(r.pixelEdge)) {
    return makeError("RAG: the split threshold must be a positive number of pixels");
  }
  if (r.edgeProbes != 1 && r.edgeProbes != 3) {
    return makeError("RAG: an edge is probed at 1 point (its midpoint) or 3 (its quarter points too), not {}",
                     r.edgeProbes);
  }
  if (!(r.heightDifferenceM >= 0.0f) || !std::isfinite(r.heightDifferenceM)) {
    return makeError("RAG: the height difference must be a finite number of metres >= 0");
  }
  if (!(r.depthDetail >= 0.0f && r.depthDetail <= 1.0f)) {
    return makeError("RAG: depth detail must be within 0 to 1");
  }
  if (!(r.morphBand >= 0.0f && r.morphBand <= 1.0f)) {
    return makeError("RAG: the morph band must be within 0 (off) to 1");
  }
  if (!(r.edgeLengthPx >= 0.0f) || !std::isfinite(r.edgeLengthPx)) {
    return makeError("RAG: the edge length to split at must be a finite number of pixels >= 0");
  }
  if (!(options.adaptiveMinGrowth >= 0.0f && options.adaptiveMinGrowth < 4.0f)) {
    return makeError("RAG: the adaptive growth threshold must be within 0 to 4");
  }
  return {};
}

}  // namespace

Result<std::unique_ptr<RagRenderer>> RagRenderer::create(const HeightGrid& grid,
                                                         const RagOptions& options) {
  if (Status ok = checkOptions(options); !ok) return ok.error();
  // The height map is one texture: a grid beyond the texture limit (or the option's) is
  // replaced by the finest pyramid level that fits.
  GLint maxTexture = 0;
  glGetIntegerv(GL_MAX_TEXTURE_SIZE, &maxTexture);
  const int maxSide = options.maxMapSamples > 0 ? std::min(options.maxMapSamples, int(maxTexture))
                                                : int(maxTexture);
  const int level = rag::heightMapLevel(grid.width, grid.height, maxSide);
  std::optional<rag::HeightMap> coarser;
  if (level > 0) {
    coarser = rag::heightMapAtLevel(grid, level);
    spdlog::info(
        "RAG: {} x {} samples exceed the height map limit of {} a side: refining against level "
        "{} ({} x {} samples, geometric error {:.2f} m{})",
        grid.width, grid.height, maxSide, level, coarser->grid.width, coarser->grid.height,
        coarser->errorM,
        coarser->droppedColumns + coarser->droppedRows > 0
            ? fmt::format("; {} columns east and {} rows north left out",
                          coarser->droppedColumns, coarser->droppedRows)
            : std::string());
  }
  const HeightGrid& map = coarser ? coarser->grid : grid;
  Result<std::vector<rag::Triangle>> coarse =
      options.alignCoarseMesh ? rag::buildAlignedCoarseMesh(map, options.coarseVertices)
                              : rag::buildCoarseMesh(map, options.coarseVertices);
  if (!coarse) return coarse.error();

  std::unique_ptr<RagRenderer> renderer(new RagRenderer());
  renderer->options_ = options;
  // Aligned cells end in the map's own cells, so refinement reads the reference's triangles.
  renderer->options_.refinement.sampling =
      options.alignCoarseMesh ? rag::MapSampling::Surface : rag::MapSampling::Nearest;
  renderer->coarse_ = std::move(coarse.value());
  renderer->spacingXM_ = map.spacingXM;
  renderer->spacingYM_ = map.spacingYM;
  renderer->heightRange_ = grid.heightRange();  // the full grid's: conservative clipping
  renderer->mapLevel_ = level;
  renderer->mapErrorM_ = coarser ? coarser->errorM : 0.0f;
  renderer->adaptivePasses_ = std::max(1, std::min(options.passes, 2));

  Result<gl::Program> refine = gl::Program::fromFiles(
      {{GL_VERTEX_SHADER, "rag/refine.vert"}, {GL_GEOMETRY_SHADER, "rag/refine.geom"}},
      {"gGrid"});
  if (!refine) return refine.error();
  renderer->refine_ = std::move(refine.value());
  Result<FillAndWirePrograms> draw = loadFillAndWirePrograms("rag/draw.vert", "rag/draw.frag");
  if (!draw) return draw.error();
  renderer->fill_ = std::move(draw->fill);
  renderer->wire_ = std::move(draw->wire);

  renderer->heights_ = gl::Texture::create2D(GL_R32F, map.width, map.height);
  renderer->heights_.upload2D(0, 0, 0, map.width, map.height, GL_RED, GL_FLOAT,
                              map.heights.data());
  renderer->heights_.setFilter(GL_LINEAR, GL_LINEAR);  // texelFetch ignores it (decisions)
  renderer->heights_.setWrap(GL_CLAMP_TO_EDGE);

  renderer->coarseBuffer_ =
      gl::Buffer(renderer->coarse_.size() * kTriangleBytes, renderer->coarse_.data());
  renderer->coarseArray_ = gl::VertexArray::create();
  renderer->coarseArray_.setVec3Positions(renderer->coarseBuffer_);
  for (int i = 0; i < 2; ++i) {
    renderer->arrays_[std::size_t(i)] = gl::VertexArray::create();
    renderer->feedback_[std::size_t(i)] = gl::TransformFeedback::create();
  }
  for (QuerySet* set : {&renderer->querySets_[0], &renderer->querySets_[1],
                        &renderer->replayQueries_}) {
    for (int p = 0; p < kRagMaxPasses; ++p) {
      set->generated[std::size_t(p)] = gl::Query::create(GL_PRIMITIVES_GENERATED);
      set->written[std::size_t(p)] = gl::Query::create(GL_TRANSFORM_FEEDBACK_PRIMITIVES_WRITTEN);
    }
  }
  renderer->allocateBuffers(
      std::max<std::uint64_t>(kMinCapacity, std::uint64_t(renderer->coarse_.size()) * 16));
  return renderer;
}

void RagRenderer::allocateBuffers(std::uint64_t triangles) {
  capacity_ = std::bit_ceil(triangles);
  for (std::size_t i = 0; i < 2; ++i) {
    buffers_[i] = gl::Buffer(capacity_ * kTriangleBytes, nullptr);
    arrays_[i].setVec3Positions(buffers_[i]);
    feedback_[i].captureInto(buffers_[i]);
  }
}

void RagRenderer::setRefinementUniforms(const gl::Program& program,
                                        const rag::RefinementView& view) const {
  const rag::RefinementSettings& r = options_.refinement;
  program.set("uClipFromRelative", view.clipFromRelative);
  program.set("uCameraGrid", view.cameraGrid);
  program.set("uGridScale", view.gridScale);
  program.set("uViewportPx", view.viewportPx);
  program.set("uFocalPx", view.focalPx);
  program.set("uNearM", view.nearM);
  program.set("uFarM", view.farM);
  program.set("uMinHeightM", view.minHeightM);
  program.set("uMaxHeightM", view.maxHeightM);
  program.set("uVariant", r.variant == rag::Variant::Oblique ? 0 : 1);
  program.set("uPixelEdge", r.pixelEdge);
  program.set("uEdgeProbes", r.edgeProbes);
  program.set("uHeightDifferenceM", r.heightDifferenceM);
  program.set("uDepthDetail", r.depthDetail);
  program.set("uMorphBand", r.variant == rag::Variant::Oblique ? r.morphBand : 0.0f);
  program.set("uMapSurface", r.sampling == rag::MapSampling::Surface ? 1 : 0);
  program.set("uEdgeLengthPx", r.variant == rag::Variant::Oblique ? r.edgeLengthPx : 0.0f);
  program.set("uEarlyClip", r.earlyClip ? 1 : 0);
}

int RagRenderer::runPasses(int passes, QuerySet& queries) {
  refine_.use();
  heights_.bindUnit(0);
  glEnable(GL_RASTERIZER_DISCARD);
  for (int p = 0; p < passes; ++p) {
    const std::size_t out = std::size_t(p % 2);
    feedback_[out].bind();
    queries.generated[std::size_t(p)].begin();
    queries.written[std::size_t(p)].begin();
    glBeginTransformFeedback(GL_TRIANGLES);
    if (p == 0) {
      coarseArray_.bind();
      glDrawArrays(GL_TRIANGLES, 0, GLsizei(coarse_.size() * 3));
    } else {
      const std::size_t in = std::size_t((p - 1) % 2);
      arrays_[in].bind();
      glDrawTransformFeedback(GL_TRIANGLES, feedback_[in].id());
    }
    glEndTransformFeedback();
    queries.written[std::size_t(p)].end();
    queries.generated[std::size_t(p)].end();
  }
  glBindTransformFeedback(GL_TRANSFORM_FEEDBACK, 0);
  glDisable(GL_RASTERIZER_DISCARD);
  queries.passes = passes;
  queries.pending = passes > 0;
  return (passes - 1) % 2;
}

bool RagRenderer::readCounts(QuerySet& queries, RagPassCounts& counts) {
  queries.pending = false;
  counts = RagPassCounts{};
  counts.passes = queries.passes;
  std::uint64_t largest = 0;
  bool overflowed = false;
  for (int p = 0; p < queries.passes; ++p) {
    const std::size_t i = std::size_t(p);
    counts.generated[i] = queries.generated[i].result();
    counts.written[i] = queries.written[i].result();
    largest = std::max(largest, counts.generated[i]);
    overflowed = overflowed || counts.generated[i] > counts.written[i];
  }
  if (overflowed) allocateBuffers(largest + largest / 2);
  return overflowed;
}

bool RagRenderer::absorbCounts(QuerySet& queries) {
  RagPassCounts counts;
  const bool overflowed = readCounts(queries, counts);
  lastCounts_ = counts;
  if (options_.adaptivePasses && !overflowed && counts.passes > 0) {
    // The first pass that added fewer than the threshold is not needed; if every pass added
    // enough, try one more.
    int next = std::min(counts.passes + 1, options_.passes);
    std::uint64_t previous = coarse_.size();
    for (int p = 0; p < counts.passes; ++p) {
      const double grown = double(counts.written[std::size_t(p)]);
      if (p > 0 && grown < double(previous) * (1.0 + double(options_.adaptiveMinGrowth))) {
        next = p;
        break;
      }
      previous = counts.written[std::size_t(p)];
    }
    adaptivePasses_ = std::max(1, next);
  }
  return overflowed;
}

void RagRenderer::noteTruncatedFrame() {
  ++overflowedFrames_;
  spdlog::warn("RAG: a frame was drawn from overflowed buffers; they now hold {} triangles",
               capacity_);
}

void RagRenderer::drawMesh(const gl::Program& program, int resultBuffer, int passes) const {
  program.use();
  heights_.bindUnit(0);
  if (passes == 0) {
    coarseArray_.bind();
    glDrawArrays(GL_TRIANGLES, 0, GLsizei(coarse_.size() * 3));
    return;
  }
  arrays_[std::size_t(resultBuffer)].bind();
  glDrawTransformFeedback(GL_TRIANGLES, feedback_[std::size_t(resultBuffer)].id());
}

FrameStats RagRenderer::draw(const ViewSetup& view, const RenderSettings& settings) {
  const rag::RefinementView refinementView = rag::RefinementView::create(
      view, spacingXM_, spacingYM_, heightRange_, settings.verticalExaggeration);
  setRefinementUniforms(refine_, refinementView);

  // The previous frame's counts, if the GPU has them (never waited for here).
  QuerySet& previous = querySets_[std::size_t((frame_ + 1) % 2)];
  if (previous.pending && previous.written[std::size_t(previous.passes - 1)].available() &&
      absorbCounts(previous)) {
    noteTruncatedFrame();
  }

  const int passes = options_.adaptivePasses ? adaptivePasses_ : options_.passes;
  QuerySet& queries = querySets_[std::size_t(frame_ % 2)];
  int result = runPasses(passes, queries);
  if (options_.exactCounts) {
    while (queries.pending && absorbCounts(queries)) result = runPasses(passes, queries);
  } else {
    // Submit the passes now, as a buffer swap would: without a flush, a headless loop that
    // reads nothing back would find the queries unfinished frame after frame.
    glFlush();
  }
  passesThisFrame_ = passes;
  ++frame_;
  previousSelection_ = currentSelection_;
  currentSelection_ = Selection{refinementView, passes};

  drawRefined(refinementView, view, settings, result, passes);

  FrameStats stats;
  stats.drawCalls = std::uint64_t(passes) + (settings.wireframe ? 2 : 1);
  stats.triangles = passes == 0 ? coarse_.size()
                                : lastCounts_.written[std::size_t(std::max(0, passes - 1))];
  stats.vertices = stats.triangles * 3;
  return stats;
}

bool RagRenderer::drawPreviousSelection(const ViewSetup& view, const RenderSettings& settings) {
  if (!previousSelection_) return false;
  // Refining is deterministic: the previous view's uniforms make the previous mesh again (in
  // buffers the next frame refines anew). Its own queries, read at once, keep the frame's
  // counts and adaptive pass count untouched.
  const Selection& previous = *previousSelection_;
  setRefinementUniforms(refine_, previous.view);
  int result = runPasses(previous.passes, replayQueries_);
  RagPassCounts counts;
  while (replayQueries_.pending && readCounts(replayQueries_, counts)) {
    result = runPasses(previous.passes, replayQueries_);
  }
  const rag::RefinementView drawView = rag::RefinementView::create(
      view, spacingXM_, spacingYM_, heightRange_, settings.verticalExaggeration);
  drawRefined(drawView, view, settings, result, previous.passes);
  return true;
}

void RagRenderer::drawRefined(const rag::RefinementView& refinementView, const ViewSetup& view,
                              const RenderSettings& settings, int resultBuffer, int passes) {
  for (const gl::Program* program : {&fill_, &wire_}) {
    setRefinementUniforms(*program, refinementView);
    program->set("uSpacing", glm::vec2(float(spacingXM_), float(spacingYM_)));
    program->set("uExaggeration", settings.verticalExaggeration);
  }
  fill_.set("uMapErrorM", mapErrorM_);
  applyShadingMode(fill_, view, settings);
  drawWithWireframeOverlay(
      settings.wireframe, wire_, view, [&] { drawMesh(fill_, resultBuffer, passes); },
      [&] { drawMesh(wire_, resultBuffer, passes); });
}

void RagRenderer::finishStats(FrameStats& stats) {
  QuerySet& queries = querySets_[std::size_t((frame_ + 1) % 2)];  // the last draw()'s
  if (!queries.pending) return;
  if (absorbCounts(queries)) {
    noteTruncatedFrame();
    stats.truncated = true;
  }
  stats.triangles = lastCounts_.written[std::size_t(queries.passes - 1)];
  stats.vertices = stats.triangles * 3;
}

std::vector<rag::Triangle> RagRenderer::refineAndRead(const ViewSetup& view,
                                                      float verticalExaggeration) {
  const rag::RefinementView refinementView = rag::RefinementView::create(
      view, spacingXM_, spacingYM_, heightRange_, verticalExaggeration);
  setRefinementUniforms(refine_, refinementView);
  const int passes = options_.passes;
  if (passes == 0) return coarse_;
  // Draws need a complete framebuffer even with the rasteriser off: an empty 1 x 1 one.
  GLint previousFramebuffer = 0;
  glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &previousFramebuffer);
  if (!emptyTarget_.id()) {
    emptyTarget_ = gl::Framebuffer::create();
    glNamedFramebufferParameteri(emptyTarget_.id(), GL_FRAMEBUFFER_DEFAULT_WIDTH, 1);
    glNamedFramebufferParameteri(emptyTarget_.id(), GL_FRAMEBUFFER_DEFAULT_HEIGHT, 1);
  }
  emptyTarget_.bind();
  QuerySet& queries = querySets_[std::size_t(frame_ % 2)];
  int result = runPasses(passes, queries);
  while (absorbCounts(queries)) result = runPasses(passes, queries);
  glBindFramebuffer(GL_FRAMEBUFFER, GLuint(previousFramebuffer));
  std::vector<rag::Triangle> mesh(lastCounts_.written[std::size_t(passes - 1)]);
  buffers_[std::size_t(result)].download(0, mesh.size() * kTriangleBytes, mesh.data());
  return mesh;
}

std::vector<std::string> RagRenderer::frameReport() const {
  std::vector<std::string> lines;
  if (mapLevel_ > 0) {
    lines.push_back(fmt::format("height map: level {} (beyond the texture limit), error {:.1f} m",
                                mapLevel_, mapErrorM_));
  }
  for (int p = 0; p < lastCounts_.passes; ++p) {
    lines.push_back(fmt::format("pass {}: {} triangles", p + 1,
                                countText(lastCounts_.written[std::size_t(p)])));
  }
  return lines;
}

}  // namespace tellus
