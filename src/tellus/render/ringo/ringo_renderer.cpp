#include "tellus/render/ringo/ringo_renderer.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdlib>
#include <limits>

#include <glm/matrix.hpp>
#include <spdlog/spdlog.h>

#include "tellus/core/frustum.hpp"
#include "tellus/core/geodesy.hpp"
#include "tellus/lod/globe/globe_mesh.hpp"
#include "tellus/lod/ringo/ringo_block_data.hpp"
#include "tellus/render/wireframe_overlay.hpp"

namespace tellus {
namespace {

// x mod m in 0 .. m - 1.
std::int64_t wrap(std::int64_t x, std::int64_t m) {
  const std::int64_t r = x % m;
  return r < 0 ? r + m : r;
}

// The shortest signed step from column `from` to column `to` round a row of `columns` tiles.
int columnStep(std::int64_t from, std::int64_t to, int columns) {
  std::int64_t step = wrap(to - from, columns);
  if (step > columns / 2) step -= columns;
  return int(step);
}

}  // namespace

Result<std::unique_ptr<RingoRenderer>> RingoRenderer::create(
    std::shared_ptr<const GlobalStore> store, RingoOptions options) {
  if (!store) return makeError("the RINGO renderer draws a global store (tellus build --global)");
  if (options.rings < 0 || options.rings > 8) {
    return makeError("RINGO takes 0 to 8 rings, got {}", options.rings);
  }
  if (options.uploadsPerFrame < 1) {
    return makeError("RINGO needs at least one upload per frame, got {}", options.uploadsPerFrame);
  }
  std::unique_ptr<RingoRenderer> renderer(new RingoRenderer());
  renderer->store_ = std::move(store);
  renderer->options_ = options;
  renderer->layout_ = {.rings = options.rings, .tileCells = renderer->store_->tileCells()};
  Result<FillAndWirePrograms> programs =
      loadFillAndWirePrograms("ringo/ringo.vert", "globe/globe.frag");
  if (!programs) return programs.error();
  renderer->fill_ = std::move(programs->fill);
  renderer->wire_ = std::move(programs->wire);
  Result<GlobeSky> sky = GlobeSky::create();
  if (!sky) return sky.error();
  renderer->sky_ = std::move(sky.value());
  return renderer;
}

RingoRenderer::~RingoRenderer() = default;

void RingoRenderer::startMatrix(int depth, const GeoTileKey& centre) {
  Matrix fresh;
  fresh.blocks.emplace(layout_, depth, centre.x, centre.y);
  fresh.slots.resize(std::size_t(fresh.blocks->slotCount()));
  fresh.reorganiser = std::make_unique<RingoReorganiser>(
      layout_, fresh.blocks->slotCount(),
      [store = store_, layout = layout_](const RingoBlock& block) {
        return loadRingoBlock(*store, layout, block);
      },
      options_.geoid);
  fresh.reorganiser->submit(ringoInitialUpdates(*fresh.blocks));
  current_ = std::move(fresh);
}

void RingoRenderer::upload(Matrix& matrix, RingoReadyBlock ready) {
  GpuBlock& slot = matrix.slots[std::size_t(ready.slot)];
  slot = GpuBlock{};
  if (!ready.block.exists) return;
  slot.block = ready.block;
  slot.bounds = ready.mesh.bounds;
  slot.cells = ready.mesh.cells;
  slot.vertices = gl::Buffer(std::span<const RingoVertex>(ready.mesh.vertices));
  slot.vertexArray = gl::VertexArray::create();
  const GLuint vao = slot.vertexArray.id();
  glVertexArrayVertexBuffer(vao, 0, slot.vertices.id(), 0, sizeof(RingoVertex));
  const auto attribute = [vao](GLuint location, GLint size, GLenum type, GLboolean normalised,
                               std::size_t offset) {
    glEnableVertexArrayAttrib(vao, location);
    glVertexArrayAttribFormat(vao, location, size, type, normalised, GLuint(offset));
    glVertexArrayAttribBinding(vao, location, 0);
  };
  // Integer attributes: no conversion to float.
  const auto integers = [vao](GLuint location, GLint size, GLenum type, std::size_t offset) {
    glEnableVertexArrayAttrib(vao, location);
    glVertexArrayAttribIFormat(vao, location, size, type, GLuint(offset));
    glVertexArrayAttribBinding(vao, location, 0);
  };
  integers(0, 3, GL_INT, offsetof(RingoVertex, whole));
  attribute(1, 3, GL_FLOAT, GL_FALSE, offsetof(RingoVertex, fraction));
  integers(2, 3, GL_INT, offsetof(RingoVertex, collapsedWhole));
  attribute(3, 3, GL_FLOAT, GL_FALSE, offsetof(RingoVertex, collapsedFraction));
  attribute(4, 4, GL_INT_2_10_10_10_REV, GL_TRUE, offsetof(RingoVertex, normal));
  attribute(5, 1, GL_FLOAT, GL_FALSE, offsetof(RingoVertex, heightM));
  integers(6, 1, GL_UNSIGNED_INT, offsetof(RingoVertex, edges));
  slot.indices = &indexBuffers_.forGrid(slot.cells + 1, slot.cells + 1);
  glVertexArrayElementBuffer(vao, slot.indices->id());
  slot.heights = std::move(ready.heights);
}

bool RingoRenderer::complete(const Matrix& matrix) const {
  if (!matrix.blocks) return false;
  for (int i = 0; i < matrix.blocks->slotCount(); ++i) {
    const RingoBlock& wanted = matrix.blocks->slot(i);
    if (wanted.exists && !(matrix.slots[std::size_t(i)].indices &&
                           matrix.slots[std::size_t(i)].block == wanted)) {
      return false;
    }
  }
  return true;
}

double RingoRenderer::groundUnderM(double latDeg, double lonDeg) const {
  const Matrix& matrix = complete(current_) || !previous_.blocks ? current_ : previous_;
  if (!matrix.blocks) return std::numeric_limits<double>::quiet_NaN();
  const GeoTileKey key = GlobalTiling::tileAt(matrix.blocks->depth(), latDeg, lonDeg);
  for (const GpuBlock& slot : matrix.slots) {
    if (!slot.indices || slot.block.key != key || slot.heights.empty()) continue;
    const GeoBounds box = GlobalTiling::bounds(key);
    const double u = (lonDeg - box.westDeg) / (box.eastDeg - box.westDeg) * slot.cells;
    const double v = (box.northDeg - latDeg) / (box.northDeg - box.southDeg) * slot.cells;
    const double h = tileSurfaceAt(slot.heights, slot.cells, u, v);
    return options_.geoid ? options_.geoid->ellipsoidalHeightM(h, latDeg, lonDeg) : h;
  }
  return std::numeric_limits<double>::quiet_NaN();
}

double RingoRenderer::storeGroundM(double latDeg, double lonDeg) const {
  const GeoTileKey key = store_->deepestStored(
      GlobalTiling::tileAt(store_->metadata().deepestDepth, latDeg, lonDeg));
  std::vector<float> heights(store_->tileShape().sampleCount());
  if (!store_->readTileMetres(key, heights)) return 0.0;
  const int n = store_->tileCells();
  const GeoBounds box = GlobalTiling::bounds(key);
  const double u = (lonDeg - box.westDeg) / (box.eastDeg - box.westDeg) * n;
  const double v = (box.northDeg - latDeg) / (box.northDeg - box.southDeg) * n;
  const double h = tileSurfaceAt(heights, n, u, v);
  return options_.geoid ? options_.geoid->ellipsoidalHeightM(h, latDeg, lonDeg) : h;
}

void RingoRenderer::prepare(const ViewSetup& view, const RenderSettings&) {
  const wgs84::Geodetic eye = wgs84::ecefToGeodetic(view.camera.position);
  const double lat = eye.latRad / wgs84::kDegree, lon = eye.lonRad / wgs84::kDegree;
  double ground = groundUnderM(lat, lon);
  if (!std::isfinite(ground)) ground = storeGroundM(lat, lon);  // before the first matrix
  const double clearance = eye.heightM - (std::isfinite(ground) ? ground : 0.0);
  const int storeDepth = store_->metadata().deepestDepth;
  const int deepest =
      store_->deepestStored(GlobalTiling::tileAt(storeDepth, lat, lon)).depth;
  const int depth = ringoDepthFor(clearance, deepest, layout_,
                                  current_.blocks ? current_.blocks->depth() : -1);
  const GeoTileKey centre = GlobalTiling::tileAt(depth, lat, lon);
  spdlog::debug("ringo: clearance {:.1f} m (ground {:.1f} m), depth {} (store {}), centre {}/{}/{}",
                clearance, ground, depth, deepest, centre.depth, centre.x, centre.y);
  if (!current_.blocks || current_.blocks->depth() != depth) {
    // The complete matrix keeps drawing until the new one is complete.
    if (complete(current_)) previous_ = std::move(current_);
    startMatrix(depth, centre);
  } else {
    RingoBlockMatrix& blocks = *current_.blocks;
    const int step = columnStep(blocks.centreX(), centre.x, GlobalTiling::tilesX(depth));
    if (step != 0 || centre.y != blocks.centreY()) {
      current_.reorganiser->submit(blocks.recentre(blocks.centreX() + step, centre.y));
    }
  }
  info_.uploads = 0;
  // Stills wait for every block; so does the very first matrix (nothing to draw meanwhile:
  // loading the scene), and a matrix whose last complete predecessor is more than one depth
  // away (a jump, not a flight: that one would show the ground of another height). Otherwise
  // the new matrix streams in while the previous one draws.
  const bool nothingToDraw =
      !previous_.blocks && std::none_of(current_.slots.begin(), current_.slots.end(),
                                        [](const GpuBlock& slot) { return slot.indices; });
  const bool jumped = previous_.blocks && std::abs(previous_.blocks->depth() - depth) > 1;
  const bool wait = options_.waitForBlocks || nothingToDraw || jumped;
  if (wait) current_.reorganiser->waitIdle();
  const std::size_t budget =
      wait ? std::numeric_limits<std::size_t>::max() : std::size_t(options_.uploadsPerFrame);
  for (RingoReadyBlock& ready : current_.reorganiser->takeReady(budget)) {
    upload(current_, std::move(ready));
    ++info_.uploads;
  }
  if (complete(current_)) previous_ = Matrix{};
  info_.depth = depth;
  info_.reorganising = !current_.reorganiser->idle();
  info_.reorganiser = current_.reorganiser->stats();
  info_.blocksResident = 0;
  for (const GpuBlock& slot : current_.slots) info_.blocksResident += slot.indices ? 1 : 0;
}

void RingoRenderer::drawMatrix(const Matrix& matrix, const gl::Program& program,
                               const ViewSetup& view, FrameStats* stats) {
  if (!matrix.blocks) return;
  program.use();
  program.set("uViewProjection", glm::mat4(view.relativeViewProjection()));
  glm::ivec3 eyeWhole;
  glm::vec3 eyeFraction;
  globe::splitEcef(view.camera.position, eyeWhole, eyeFraction);
  program.set("uEyeWhole", eyeWhole);
  program.set("uEyeFraction", eyeFraction);
  const Frustum frustum = Frustum::fromMatrix(view.relativeViewProjection());
  const RingoBlockMatrix& blocks = *matrix.blocks;
  const int columns = GlobalTiling::tilesX(blocks.depth());
  const int half = layout_.side() / 2;
  const glm::dvec3& eye = view.camera.position;
  for (const GpuBlock& slot : matrix.slots) {
    if (!slot.indices) continue;
    if (!frustum.intersects({slot.bounds.min - eye, slot.bounds.max - eye})) continue;
    const int dx = columnStep(wrap(blocks.centreX(), columns), slot.block.key.x, columns);
    const int dy = slot.block.key.y - blocks.centreY();
    const std::uint32_t coarser = std::abs(dx) <= half && std::abs(dy) <= half
                                      ? ringoCoarserEdges(dx, dy, layout_)
                                      : 0u;
    program.set("uCoarserEdges", int(coarser));
    slot.vertexArray.bind();
    const auto indexCount = GLsizei(slot.indices->size() / sizeof(std::uint32_t));
    glDrawElements(GL_TRIANGLES, indexCount, GL_UNSIGNED_INT, nullptr);
    if (stats) {
      stats->triangles += std::uint64_t(indexCount / 3);
      stats->vertices += std::uint64_t(slot.cells + 1) * std::uint64_t(slot.cells + 1);
      ++stats->drawCalls;
      ++info_.blocksDrawn;
    }
  }
}

FrameStats RingoRenderer::draw(const ViewSetup& view, const RenderSettings& settings) {
  const glm::vec3 sun = globeSunEcef(view, settings);
  if (settings.sky) sky_->draw(view, sun);
  setGlobeFillUniforms(fill_, view, settings, sun);
  fill_.set("uDrapeEnabled", false);
  const Matrix& drawn = complete(current_) || !previous_.blocks ? current_ : previous_;
  // wire.frag fades lines by the cell size: the central blocks' cells on the ground.
  const double cellM = drawn.blocks ? GlobalTiling::tileSizeDeg(drawn.blocks->depth()) *
                                          111'320.0 / layout_.tileCells
                                    : 1.0;
  wire_.set("uSpacing", glm::vec2(float(cellM), float(cellM)));
  FrameStats stats;
  info_.blocksDrawn = 0;
  drawWithWireframeOverlay(
      settings.wireframe, wire_, view, [&] { drawMatrix(drawn, fill_, view, &stats); },
      [&] { drawMatrix(drawn, wire_, view, nullptr); });
  return stats;
}

}  // namespace tellus
