#include "tellus/render/gamer/gamer_renderer.hpp"

#include <spdlog/spdlog.h>

#include "tellus/core/thread_cpu_clock.hpp"


namespace tellus {

Result<std::unique_ptr<GamerRenderer>> GamerRenderer::create(const HeightGrid& grid, const GamerOptions& options) {
  if (!(options.settings.targetPx > 0.0f)) return makeError("GAMeR error target must be > 0 px");
  if (!(options.settings.morphBand >= 0.0f && options.settings.morphBand <= 1.0f)) {
    return makeError("GAMeR morph band {} is outside [0, 1]", options.settings.morphBand);
  }
  GLint maxTexture = 0;
  glGetIntegerv(GL_MAX_TEXTURE_SIZE, &maxTexture);
  if (grid.width > maxTexture || grid.height > maxTexture) {
    return makeError("GAMeR reads its geometry from one height texture: the {} x {} grid exceeds this "
                     "GPU's {} texels a side",
                     grid.width, grid.height, maxTexture);
  }
  Result<gamer::PatternPool> pool = gamer::PatternPool::build(options.settings.maxDepth);
  if (!pool) return pool.error();
  Result<gamer::CoarseTerrain> terrain = gamer::CoarseTerrain::create(grid, options.settings.maxDepth);
  if (!terrain) return terrain.error();
  std::unique_ptr<GamerRenderer> r(new GamerRenderer());
  r->options_ = options;
  r->pool_ = std::move(pool.value());
  r->terrain_ = std::move(terrain.value());
  Result<GridMeshShading> shading = GridMeshShading::create(grid, "gamer/gamer.vert", "GAMeR");
  if (!shading) return shading.error();
  r->shading_ = std::move(shading.value());
  for (const gl::Program* program : r->shading_.programs()) {
    program->set("uLatticeSteps", r->pool_.latticeSteps);
    program->set("uCellSide", 1 << r->pool_.maxDepth);
    program->set("uMaxDepth", r->pool_.maxDepth);
  }
  r->lattice_ = gl::Buffer(std::span<const glm::u16vec2>(r->pool_.vertices));
  r->patternIndices_ = gl::Buffer(std::span<const std::uint16_t>(r->pool_.indices));
  Result<GamerGpuSelection> selection = GamerGpuSelection::create(r->terrain_, r->pool_);
  if (!selection) return selection.error();
  r->selection_ = std::make_unique<GamerGpuSelection>(std::move(selection.value()));
  for (Frame& f : r->frames_) {
    f.output = r->selection_->makeOutput();
    f.array = gl::VertexArray::create();
    const GLuint vao = f.array.id();
    glVertexArrayVertexBuffer(vao, 0, r->lattice_.id(), 0, GLsizei(sizeof(glm::u16vec2)));
    glEnableVertexArrayAttrib(vao, 0);
    glVertexArrayAttribIFormat(vao, 0, 2, GL_UNSIGNED_SHORT, 0);
    glVertexArrayAttribBinding(vao, 0, 0);
    glVertexArrayVertexBuffer(vao, 1, f.output.instances.id(), 0, GLsizei(sizeof(gamer::Instance)));
    glEnableVertexArrayAttrib(vao, 1);
    glVertexArrayAttribIFormat(vao, 1, 4, GL_UNSIGNED_INT, 0);
    glVertexArrayAttribBinding(vao, 1, 1);
    glVertexArrayBindingDivisor(vao, 1, 1);
    f.array.setIndexBuffer(r->patternIndices_);
  }
  spdlog::info("GAMeR: {} patterns up to depth {} ({:.1f} KiB), {} x {} coarse cells", r->pool_.patterns.size(),
               options.settings.maxDepth, double(r->pool_.bytes()) / 1024.0, r->terrain_.cellsX(),
               r->terrain_.cellsY());
  return r;
}

void GamerRenderer::prepare(const ViewSetup& view, const RenderSettings& settings) {
  const LodView lodView = LodView::fromSetup(view, settings.verticalExaggeration);
  current_ = 1 - current_;
  const double start = threadCpuSeconds();
  selection_->run(lodView, options_.settings, frames_[std::size_t(current_)].output);
  runThreadMs_ = (threadCpuSeconds() - start) * 1e3;
  prepared_ = true;
}

FrameStats GamerRenderer::draw(const ViewSetup& view, const RenderSettings& settings) {
  if (!prepared_) prepare(view, settings);  // a caller that does not prepare (stills)
  prepared_ = false;
  drawFrame(frames_[std::size_t(current_)], view, settings);
  ++framesDrawn_;
  // The counts of the newest frame the GPU has finished (this one's arrive later).
  for (int k : {current_, 1 - current_}) {
    if (const auto totals = GamerGpuSelection::totalsIfDone(frames_[std::size_t(k)].output)) {
      lastTotals_ = *totals;
      break;
    }
  }
  FrameStats stats;
  stats.triangles = lastTotals_.triangles;
  stats.vertices = stats.triangles * 3;
  stats.drawCalls = 1;
  stats.stageMs["classify_dispatch_thread"] = runThreadMs_;
  return stats;
}

void GamerRenderer::finishStats(FrameStats& stats) {
  lastTotals_ = GamerGpuSelection::readTotals(frames_[std::size_t(current_)].output);
  stats.triangles = lastTotals_.triangles;
  stats.vertices = stats.triangles * 3;
  stats.drawCalls = lastTotals_.coarseTriangles > 0 ? 1 : 0;
}

bool GamerRenderer::drawPreviousSelection(const ViewSetup& view, const RenderSettings& settings) {
  if (framesDrawn_ < 2) return false;
  drawFrame(frames_[std::size_t(1 - current_)], view, settings);
  return true;
}

void GamerRenderer::drawFrame(const Frame& frame, const ViewSetup& view, const RenderSettings& settings) {
  shading_.draw(view, settings, [&](const gl::Program& program) {
    program.use();
    frame.array.bind();
    // One command a pattern; the GPU skips those no coarse triangle chose (0 instances).
    glBindBuffer(GL_DRAW_INDIRECT_BUFFER, frame.output.commands.id());
    glMultiDrawElementsIndirect(GL_TRIANGLES, GL_UNSIGNED_SHORT, nullptr, selection_->patternCount(), 0);
    glBindBuffer(GL_DRAW_INDIRECT_BUFFER, 0);
  });
}

std::vector<std::string> GamerRenderer::frameReport() const {
  const GamerGpuSelection::Totals& t = lastTotals_;
  return {fmt::format("coarse triangles {}, patterns in use {} of {} (a frame or two late)",
                      countText(t.coarseTriangles), t.patternsUsed, pool_.patterns.size()),
          fmt::format("refined triangles {}", countText(t.triangles)),
          fmt::format("pattern pool {:.1f} KiB", double(pool_.bytes()) / 1024.0)};
}

}  // namespace tellus
