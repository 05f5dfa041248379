#include "tellus/render/globe/globe_reference_renderer.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>

#include <fmt/format.h>
#include <tbb/parallel_for.h>
#include <glm/matrix.hpp>

#include "tellus/core/enu_frame.hpp"
#include "tellus/core/frustum.hpp"
#include "tellus/core/geodesy.hpp"
#include "tellus/lod/globe/globe_store_cut.hpp"
#include "tellus/render/drawing/wireframe_overlay.hpp"

namespace tellus {
namespace {

// The smaller side of a grid cell at the grid's middle latitude, metres.
float gridCellM(const HeightGrid& grid) {
  const double midLatRad = globe::sampleLatitudeDeg(grid, 0.5 * (grid.height - 1)) * wgs84::kDegree;
  const double stepRad = std::abs(grid.georef.geoTransform[1]) * wgs84::kDegree;
  return float(std::max(1.0, std::min(wgs84::northSouthMetres(midLatRad, stepRad),
                                      wgs84::eastWestMetres(midLatRad, stepRad))));
}

// EGM96's undulation stays within -107..86 m: the margin a geoid adds to stored heights.
constexpr double kGeoidMarginM = 110.0;

}  // namespace

Status GlobeReferenceRenderer::initialise(const DrapeImage* drape) {
  Result<FillAndWirePrograms> programs = loadFillAndWirePrograms("globe/globe.vert", "globe/globe.frag");
  if (!programs) return programs.error();
  fill_ = std::move(programs->fill);
  wire_ = std::move(programs->wire);
  Result<GlobeSky> sky = GlobeSky::create();
  if (!sky) return sky.error();
  sky_ = std::move(sky.value());
  if (drape) {
    const RgbImage& image = drape->image;
    const int levels = 1 + int(std::floor(std::log2(double(std::max(image.width, image.height)))));
    drape_ = gl::Texture::create2D(GL_RGB8, image.width, image.height, levels);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    drape_.upload2D(0, 0, 0, image.width, image.height, GL_RGB, GL_UNSIGNED_BYTE,
                    image.pixels.data());
    glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
    glGenerateTextureMipmap(drape_.id());
    drape_.setFilter(GL_LINEAR_MIPMAP_LINEAR, GL_LINEAR);
    glTextureParameteri(drape_.id(), GL_TEXTURE_WRAP_S, GL_REPEAT);
    glTextureParameteri(drape_.id(), GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    drapeBox_ = glm::vec4(float(drape->westDeg), float(drape->northDeg),
                          float(drape->eastDeg - drape->westDeg),
                          float(drape->southDeg - drape->northDeg));
  }
  return {};
}

GlobeReferenceRenderer::Chunk GlobeReferenceRenderer::upload(globe::GlobeChunk& source, float cellM) {
  Chunk chunk;
  chunk.vertices = gl::Buffer(std::span<const globe::GlobeVertex>(source.vertices));
  chunk.vertexArray = gl::VertexArray::create();
  const GLuint vao = chunk.vertexArray.id();
  glVertexArrayVertexBuffer(vao, 0, chunk.vertices.id(), 0, sizeof(globe::GlobeVertex));
  const auto attribute = [vao](GLuint location, GLint size, GLenum type, GLboolean normalised,
                               std::size_t offset) {
    glEnableVertexArrayAttrib(vao, location);
    glVertexArrayAttribFormat(vao, location, size, type, normalised, GLuint(offset));
    glVertexArrayAttribBinding(vao, location, 0);
  };
  glEnableVertexArrayAttrib(vao, 0);  // integer attribute: no conversion to float
  glVertexArrayAttribIFormat(vao, 0, 3, GL_INT, GLuint(offsetof(globe::GlobeVertex, whole)));
  glVertexArrayAttribBinding(vao, 0, 0);
  attribute(1, 3, GL_FLOAT, GL_FALSE, offsetof(globe::GlobeVertex, fraction));
  attribute(2, 4, GL_INT_2_10_10_10_REV, GL_TRUE, offsetof(globe::GlobeVertex, normal));
  attribute(3, 1, GL_FLOAT, GL_FALSE, offsetof(globe::GlobeVertex, heightM));
  chunk.indices = &indexBuffers_.forGrid(source.vertsX, source.vertsY);
  glVertexArrayElementBuffer(vao, chunk.indices->id());
  chunk.vertsX = source.vertsX;
  chunk.vertsY = source.vertsY;
  chunk.ecefBounds = source.ecefBounds;
  chunk.cellM = cellM;
  source.vertices = {};  // free the CPU copy as we go
  return chunk;
}

Result<GlobeReferenceRenderer> GlobeReferenceRenderer::create(const HeightGrid& grid,
                                                              const Geoid* geoid,
                                                              const DrapeImage* drape) {
  Result<globe::GlobeMesh> mesh =
      globe::buildGlobeMesh(grid, geoid, GlobeReferenceRenderer::kChunkQuads);
  if (!mesh) return mesh.error();
  GlobeReferenceRenderer renderer;
  if (Status s = renderer.initialise(drape); !s) return s.error();
  renderer.triangles_ = mesh->triangleCount;
  renderer.cellM_ = gridCellM(grid);
  const HeightRange range = grid.heightRange();
  renderer.highestM_ = range.maxM + (geoid ? 90.0 : 0.0);  // EGM96 stays within -107..86 m
  renderer.lowestM_ = range.minM - (geoid ? 110.0 : 0.0);
  for (globe::GlobeChunk& source : mesh->chunks) {
    renderer.chunks_.push_back(renderer.upload(source, renderer.cellM_));
  }
  return renderer;
}

Result<GlobeReferenceRenderer> GlobeReferenceRenderer::create(
    std::shared_ptr<const GlobalStore> store, const Geoid* geoid, const DrapeImage* drape,
    double tolerancePx) {
  if (!store) return makeError("the globe reference needs a global store");
  if (!(tolerancePx > 0.0)) return makeError("a tolerance of {} px: it must be above 0", tolerancePx);
  GlobeReferenceRenderer renderer;
  if (Status s = renderer.initialise(drape); !s) return s.error();
  const GlobalStoreMetadata& metadata = store->metadata();
  renderer.highestM_ = double(metadata.maxHeightM) + (geoid ? 90.0 : 0.0);  // as create(grid)
  renderer.lowestM_ = double(metadata.minHeightM) - (geoid ? kGeoidMarginM : 0.0);
  renderer.store_ = std::move(store);
  renderer.geoid_ = geoid;
  renderer.tolerancePx_ = tolerancePx;
  return renderer;
}

Result<GlobeReferenceRenderer::TileMesh> GlobeReferenceRenderer::makeTileMesh(GeoTileKey key) const {
  Result<HeightGrid> grid = readGlobalTileSurface(*store_, key);
  if (!grid) return grid.error();
  // The skirt must reach below a neighbour's edge where the two differ: a neighbour of another
  // depth differs from this tile's edge by at most both tiles' errors. Neighbours are mostly
  // this depth or the parent's (the cut refines by distance), so four times the parent's error,
  // with 20 m to spare, covers the gap; where a neighbour is coarser still, its error is within
  // the tolerance on screen, and so is any gap left. (The GPU test's descent shows holes without
  // skirts and none with them.)
  const double parentErrorM = globe::globeStoreTileErrorM(*store_, GlobalTiling::parent(key));
  const double skirtM = 4.0 * parentErrorM + 20.0;
  Result<globe::GlobeMesh> mesh =
      globe::buildGlobeMesh(grid.value(), geoid_, store_->tileCells() + 2, skirtM);
  if (!mesh) return mesh.error();
  return TileMesh{std::move(mesh.value()), gridCellM(grid.value())};
}

void GlobeReferenceRenderer::prepare(const ViewSetup& view, const RenderSettings&) {
  if (!store_) return;
  ++frame_;
  globe::GlobeStoreCutView cutView;
  cutView.eyeEcef = view.camera.position;
  cutView.frustum = Frustum::fromMatrix(view.relativeViewProjection());
  cutView.focalPx = view.projection[1][1] * 0.5 * double(view.height);
  globe::GlobeStoreCutOptions options;
  options.tolerancePx = tolerancePx_;
  options.heightMarginM = geoid_ ? kGeoidMarginM : 0.0;
  const globe::GlobeStoreCut cut = globe::cutGlobeStore(*store_, cutView, options);
  cutTiles_ = cut.tiles.size();
  cutDepths_ = {GlobalTiling::kMaxDepth, 0};
  for (const GeoTileKey key : cut.tiles) {
    cutDepths_ = {std::min(cutDepths_.first, key.depth), std::max(cutDepths_.second, key.depth)};
  }
  cutCapped_ = cut.capped;
  cutWorstPx_ = cut.worstErrorPx;
  tilesMade_ = 0;
  // Meshes for the tiles that just came into view, made on every core (reading and decoding
  // the store, the ECEF positions), then uploaded here.
  std::vector<GeoTileKey> missing;
  for (const GeoTileKey key : cut.tiles) {
    if (!storeTiles_.count(key)) missing.push_back(key);
  }
  std::vector<std::optional<Result<TileMesh>>> made(missing.size());
  tbb::parallel_for(std::size_t(0), missing.size(),
                    [&](std::size_t i) { made[i].emplace(makeTileMesh(missing[i])); });
  for (std::size_t i = 0; i < missing.size(); ++i) {
    Result<TileMesh>& mesh = *made[i];
    if (!mesh) {
      if (!dataError_) dataError_ = mesh.error();
      continue;  // drawn without it; dataError() tells the caller
    }
    StoreTile tile;
    for (globe::GlobeChunk& source : mesh->mesh.chunks) {
      tile.chunks.push_back(upload(source, mesh->cellM));
    }
    storeTiles_.emplace(missing[i], std::move(tile));
    ++tilesMade_;
  }
  previous_ = std::move(drawn_);
  drawn_.clear();
  for (const GeoTileKey key : cut.tiles) {
    const auto it = storeTiles_.find(key);
    if (it == storeTiles_.end()) continue;  // it failed to read
    it->second.lastFrame = frame_;
    for (const Chunk& chunk : it->second.chunks) drawn_.push_back(&chunk);
  }
  // Tiles neither this frame nor the one before drew are dropped (the previous frame's stay
  // for drawPreviousSelection).
  std::erase_if(storeTiles_, [&](const auto& entry) { return entry.second.lastFrame + 1 < frame_; });
}

void GlobeReferenceRenderer::drawChunks(const gl::Program& program, const ViewSetup& view,
                                        const std::vector<const Chunk*>& chunks,
                                        FrameStats* stats) {
  program.use();
  const glm::dvec3& eye = view.camera.position;
  glm::ivec3 eyeWhole;
  glm::vec3 eyeFraction;
  globe::splitEcef(eye, eyeWhole, eyeFraction);
  program.set("uViewProjection", glm::mat4(view.relativeViewProjection()));
  program.set("uEyeWhole", eyeWhole);
  program.set("uEyeFraction", eyeFraction);
  const bool wire = &program == &wire_;
  const Frustum frustum = Frustum::fromMatrix(view.relativeViewProjection());
  for (const Chunk* chunk : chunks) {
    const Aabb relative{chunk->ecefBounds.min - eye, chunk->ecefBounds.max - eye};
    if (!frustum.intersects(relative)) continue;
    if (wire) wire_.set("uSpacing", glm::vec2(chunk->cellM, chunk->cellM));  // line fading
    chunk->vertexArray.bind();
    const auto indexCount = GLsizei(chunk->indices->size() / sizeof(std::uint32_t));
    glDrawElements(GL_TRIANGLES, indexCount, GL_UNSIGNED_INT, nullptr);
    if (stats) {
      stats->triangles += std::uint64_t(indexCount / 3);
      stats->vertices += std::uint64_t(chunk->vertsX) * std::uint64_t(chunk->vertsY);
      ++stats->drawCalls;
    }
  }
}

void GlobeReferenceRenderer::drawFrame(const ViewSetup& view, const RenderSettings& settings,
                                       const std::vector<const Chunk*>& chunks, FrameStats* stats) {
  const glm::vec3 sun = globeSunEcef(view, settings);
  if (settings.sky) sky_->draw(view, sun);
  setGlobeFillUniforms(fill_, view, settings, sun);
  fill_.set("uDrapeEnabled", drape_.id() != 0);
  if (drape_.id() != 0) {
    drape_.bindUnit(0);
    fill_.set("uDrape", 0);
    fill_.set("uDrapeBox", drapeBox_);
  }
  drawWithWireframeOverlay(
      settings.wireframe, wire_, view, [&] { drawChunks(fill_, view, chunks, stats); },
      [&] { drawChunks(wire_, view, chunks, nullptr); });
}

FrameStats GlobeReferenceRenderer::draw(const ViewSetup& view, const RenderSettings& settings) {
  FrameStats stats;
  if (store_) {
    drawFrame(view, settings, drawn_, &stats);
    stats.tilesWanted = cutTiles_;
    stats.tilesLoaded = tilesMade_;
    stats.tilesResident = storeTiles_.size();
    return stats;
  }
  std::vector<const Chunk*> all;
  all.reserve(chunks_.size());
  for (const Chunk& chunk : chunks_) all.push_back(&chunk);
  drawFrame(view, settings, all, &stats);
  return stats;
}

bool GlobeReferenceRenderer::drawPreviousSelection(const ViewSetup& view,
                                                   const RenderSettings& settings) {
  if (!store_ || previous_.empty()) return false;  // a grid's geometry never changes
  RenderSettings plain = settings;
  plain.sky = false;
  plain.wireframe = false;
  drawFrame(view, plain, previous_, nullptr);
  return true;
}

std::vector<std::string> GlobeReferenceRenderer::frameReport() const {
  if (!store_) return {};
  return {fmt::format("store cut: {} tiles of depths {}..{} within {} px of the finest data ({} "
                      "made this frame, {} resident)",
                      cutTiles_, cutDepths_.first, cutDepths_.second, tolerancePx_, tilesMade_,
                      storeTiles_.size()),
          fmt::format("worst tile error {:.3f} px{}", cutWorstPx_,
                      cutCapped_ ? fmt::format(", {} tiles left coarser by the cap", cutCapped_)
                                 : std::string())};
}

}  // namespace tellus
