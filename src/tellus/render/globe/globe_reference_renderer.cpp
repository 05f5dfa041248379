#include "tellus/render/globe/globe_reference_renderer.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>

#include <glm/matrix.hpp>

#include "tellus/core/enu_frame.hpp"
#include "tellus/core/frustum.hpp"
#include "tellus/core/geodesy.hpp"
#include "tellus/lod/globe/globe_mesh.hpp"
#include "tellus/render/drawing/wireframe_overlay.hpp"

namespace tellus {

Result<GlobeReferenceRenderer> GlobeReferenceRenderer::create(const HeightGrid& grid,
                                                              const Geoid* geoid,
                                                              const DrapeImage* drape) {
  Result<globe::GlobeMesh> mesh =
      globe::buildGlobeMesh(grid, geoid, GlobeReferenceRenderer::kChunkQuads);
  if (!mesh) return mesh.error();
  GlobeReferenceRenderer renderer;
  Result<FillAndWirePrograms> programs = loadFillAndWirePrograms("globe/globe.vert", "globe/globe.frag");
  if (!programs) return programs.error();
  renderer.fill_ = std::move(programs->fill);
  renderer.wire_ = std::move(programs->wire);
  Result<GlobeSky> sky = GlobeSky::create();
  if (!sky) return sky.error();
  renderer.sky_ = std::move(sky.value());
  if (drape) {
    const RgbImage& image = drape->image;
    const int levels = 1 + int(std::floor(std::log2(double(std::max(image.width, image.height)))));
    renderer.drape_ = gl::Texture::create2D(GL_RGB8, image.width, image.height, levels);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    renderer.drape_.upload2D(0, 0, 0, image.width, image.height, GL_RGB, GL_UNSIGNED_BYTE,
                             image.pixels.data());
    glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
    glGenerateTextureMipmap(renderer.drape_.id());
    renderer.drape_.setFilter(GL_LINEAR_MIPMAP_LINEAR, GL_LINEAR);
    glTextureParameteri(renderer.drape_.id(), GL_TEXTURE_WRAP_S, GL_REPEAT);
    glTextureParameteri(renderer.drape_.id(), GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    renderer.drapeBox_ = glm::vec4(float(drape->westDeg), float(drape->northDeg),
                                   float(drape->eastDeg - drape->westDeg),
                                   float(drape->southDeg - drape->northDeg));
  }
  renderer.triangles_ = mesh->triangleCount;
  // The smaller cell side at the grid's middle latitude (a metre of latitude is ~1/111 km).
  const double midLatRad = globe::sampleLatitudeDeg(grid, 0.5 * (grid.height - 1)) * wgs84::kDegree;
  const double stepRad = std::abs(grid.georef.geoTransform[1]) * wgs84::kDegree;
  renderer.cellM_ = float(std::max(1.0, std::min(wgs84::northSouthMetres(midLatRad, stepRad),
                                                  wgs84::eastWestMetres(midLatRad, stepRad))));
  const HeightRange range = grid.heightRange();
  renderer.highestM_ = range.maxM + (geoid ? 90.0 : 0.0);  // EGM96 stays within -107..86 m
  renderer.lowestM_ = range.minM - (geoid ? 110.0 : 0.0);
  for (globe::GlobeChunk& source : mesh->chunks) {
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
    chunk.indices = &renderer.indexBuffers_.forGrid(source.vertsX, source.vertsY);
    glVertexArrayElementBuffer(vao, chunk.indices->id());
    chunk.vertsX = source.vertsX;
    chunk.vertsY = source.vertsY;
    chunk.ecefBounds = source.ecefBounds;
    source.vertices = {};  // free the CPU copy as we go
    renderer.chunks_.push_back(std::move(chunk));
  }
  return renderer;
}

void GlobeReferenceRenderer::drawChunks(const gl::Program& program, const ViewSetup& view,
                                        FrameStats* stats) {
  program.use();
  const glm::dvec3& eye = view.camera.position;
  glm::ivec3 eyeWhole;
  glm::vec3 eyeFraction;
  globe::splitEcef(eye, eyeWhole, eyeFraction);
  program.set("uViewProjection", glm::mat4(view.relativeViewProjection()));
  program.set("uEyeWhole", eyeWhole);
  program.set("uEyeFraction", eyeFraction);
  const Frustum frustum = Frustum::fromMatrix(view.relativeViewProjection());
  for (const Chunk& chunk : chunks_) {
    const Aabb relative{chunk.ecefBounds.min - eye, chunk.ecefBounds.max - eye};
    if (!frustum.intersects(relative)) continue;
    chunk.vertexArray.bind();
    const auto indexCount = GLsizei(chunk.indices->size() / sizeof(std::uint32_t));
    glDrawElements(GL_TRIANGLES, indexCount, GL_UNSIGNED_INT, nullptr);
    if (stats) {
      stats->triangles += std::uint64_t(indexCount / 3);
      stats->vertices += std::uint64_t(chunk.vertsX) * std::uint64_t(chunk.vertsY);
      ++stats->drawCalls;
    }
  }
}

FrameStats GlobeReferenceRenderer::draw(const ViewSetup& view, const RenderSettings& settings) {
  const glm::vec3 sun = globeSunEcef(view, settings);
  if (settings.sky) sky_->draw(view, sun);
  setGlobeFillUniforms(fill_, view, settings, sun);
  fill_.set("uDrapeEnabled", drape_.id() != 0);
  if (drape_.id() != 0) {
    drape_.bindUnit(0);
    fill_.set("uDrape", 0);
    fill_.set("uDrapeBox", drapeBox_);
  }
  wire_.set("uSpacing", glm::vec2(cellM_, cellM_));  // wire.frag fades lines by cell size
  FrameStats stats;
  drawWithWireframeOverlay(
      settings.wireframe, wire_, view, [&] { drawChunks(fill_, view, &stats); },
      [&] { drawChunks(wire_, view, nullptr); });
  return stats;
}

}  // namespace tellus
