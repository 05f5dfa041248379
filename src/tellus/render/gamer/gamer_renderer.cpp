#include "tellus/render/gamer/gamer_renderer.hpp"

#include <spdlog/spdlog.h>


namespace tellus {
namespace {

struct DrawElementsIndirectCommand {  // GL's layout for glMultiDrawElementsIndirect
  GLuint count;
  GLuint instanceCount;
  GLuint firstIndex;
  GLint baseVertex;
  GLuint baseInstance;
};

}  // namespace

Result<std::unique_ptr<GamerRenderer>> GamerRenderer::create(const HeightGrid& grid, const GamerOptions& options) {
  if (!(options.settings.targetPx > 0.0f)) return makeError("GAMeR error target must be > 0 px");
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
  }
  r->lattice_ = gl::Buffer(std::span<const glm::u16vec2>(r->pool_.vertices));
  r->patternIndices_ = gl::Buffer(std::span<const std::uint16_t>(r->pool_.indices));
  for (Frame& f : r->frames_) {
    f.array = gl::VertexArray::create();
    f.commands = gl::Buffer(r->pool_.patterns.size() * sizeof(DrawElementsIndirectCommand), nullptr,
                            GL_DYNAMIC_STORAGE_BIT);
    const GLuint vao = f.array.id();
    glVertexArrayVertexBuffer(vao, 0, r->lattice_.id(), 0, GLsizei(sizeof(glm::u16vec2)));
    glEnableVertexArrayAttrib(vao, 0);
    glVertexArrayAttribIFormat(vao, 0, 2, GL_UNSIGNED_SHORT, 0);
    glVertexArrayAttribBinding(vao, 0, 0);
    glEnableVertexArrayAttrib(vao, 1);
    glVertexArrayAttribIFormat(vao, 1, 2, GL_UNSIGNED_INT, 0);
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
  terrain_.depthTags(lodView, options_.settings.targetPx, tags_);
  terrain_.select(lodView, options_.settings, pool_, tags_, pending_);
  prepared_ = true;
}

FrameStats GamerRenderer::draw(const ViewSetup& view, const RenderSettings& settings) {
  if (!prepared_) prepare(view, settings);  // a caller that does not prepare (stills)
  prepared_ = false;
  current_ = 1 - current_;
  Frame& f = frames_[std::size_t(current_)];
  std::swap(f.selection, pending_);
  const gamer::Selection& s = f.selection;
  // Instances, sorted by pattern, and one command per pattern in use.
  const std::size_t bytes = s.instances.size() * sizeof(gamer::Instance);
  if (s.instances.size() > f.instanceCapacity) {
    f.instanceCapacity = std::max<std::size_t>(s.instances.size() + s.instances.size() / 2, 4096);
    f.instances = gl::Buffer(f.instanceCapacity * sizeof(gamer::Instance), nullptr, GL_DYNAMIC_STORAGE_BIT);
    glVertexArrayVertexBuffer(f.array.id(), 1, f.instances.id(), 0, GLsizei(sizeof(gamer::Instance)));
  }
  if (bytes > 0) f.instances.upload(0, bytes, s.instances.data());
  std::vector<DrawElementsIndirectCommand> commands;
  for (std::size_t p = 0; p < pool_.patterns.size(); ++p) {
    if (s.instanceCount[p] == 0) continue;
    commands.push_back({pool_.patterns[p].indexCount, s.instanceCount[p], pool_.patterns[p].firstIndex, 0,
                        s.firstInstance[p]});
  }
  if (!commands.empty()) f.commands.upload(0, commands.size() * sizeof(DrawElementsIndirectCommand), commands.data());
  f.commandCount = GLsizei(commands.size());
  drawFrame(f, view, settings);
  ++framesDrawn_;
  FrameStats stats;
  stats.triangles = s.triangles;
  stats.vertices = s.triangles * 3;
  stats.drawCalls = commands.empty() ? 0 : 1;
  stats.uploadBytes = bytes + commands.size() * sizeof(DrawElementsIndirectCommand);
  return stats;
}

bool GamerRenderer::drawPreviousSelection(const ViewSetup& view, const RenderSettings& settings) {
  if (framesDrawn_ < 2) return false;
  drawFrame(frames_[std::size_t(1 - current_)], view, settings);
  return true;
}

void GamerRenderer::drawFrame(const Frame& frame, const ViewSetup& view, const RenderSettings& settings) {
  shading_.draw(view, settings, [&](const gl::Program& program) {
    if (frame.commandCount == 0) return;
    program.use();
    frame.array.bind();
    glBindBuffer(GL_DRAW_INDIRECT_BUFFER, frame.commands.id());
    glMultiDrawElementsIndirect(GL_TRIANGLES, GL_UNSIGNED_SHORT, nullptr, frame.commandCount, 0);
    glBindBuffer(GL_DRAW_INDIRECT_BUFFER, 0);
  });
}

std::vector<std::string> GamerRenderer::frameReport() const {
  const gamer::Selection& f = lastSelection();
  std::size_t used = 0;
  for (std::uint32_t n : f.instanceCount) used += n > 0 ? 1 : 0;
  return {fmt::format("coarse triangles {}, patterns in use {} of {}", countText(f.coarseTriangles),
                      used, f.instanceCount.size()),
          fmt::format("refined triangles {}", countText(f.triangles)),
          fmt::format("pattern pool {:.1f} KiB", double(pool_.bytes()) / 1024.0)};
}

}  // namespace tellus
