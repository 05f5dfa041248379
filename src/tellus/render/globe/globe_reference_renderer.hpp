#pragma once
// The globe reference renderer (`--algo globe-reference`): every sample of a latitude/longitude
// DEM as a vertex on the WGS84 ellipsoid (globe::buildGlobeMesh), two triangles a cell, no LOD;
// the ground truth the globe renderers are measured against, as `reference` is on the flat
// world. Draws with a ViewSetup in ECEF (geoViewSetup); positions are formed relative to the eye
// from split floats on the GPU, so the surface is stable to sub-millimetres anywhere on Earth.
// Chunks outside the frustum are skipped. The vertical exaggeration is not applied (the mesh
// holds true heights). Optionally draped with a colour map (Blue Marble), and with
// RenderSettings::sky an atmosphere behind the globe (sky.frag). Needs a current GL 4.5 context
// for its whole life.
#include <cstdint>
#include <optional>
#include <vector>

#include "tellus/core/aabb.hpp"
#include "tellus/dem/drape_image.hpp"
#include "tellus/dem/geoid.hpp"
#include "tellus/dem/height_grid.hpp"
#include "tellus/gl/buffer.hpp"
#include "tellus/gl/program.hpp"
#include "tellus/gl/texture.hpp"
#include "tellus/gl/vertex_array.hpp"
#include "tellus/render/globe/globe_shading.hpp"
#include "tellus/render/drawing/grid_index_buffers.hpp"
#include "tellus/render/terrain_renderer.hpp"

namespace tellus {

class GlobeReferenceRenderer final : public TerrainRenderer {
 public:
  static constexpr int kChunkQuads = 256;

  // `geoid` may be null: heights are then taken as ellipsoidal. `drape` (may be null): a colour
  // map drawn instead of the hypsometric tint (uploaded; not kept). Errors: a DEM that is not in
  // latitude/longitude, shaders that do not build.
  static Result<GlobeReferenceRenderer> create(const HeightGrid& grid, const Geoid* geoid,
                                               const DrapeImage* drape = nullptr);

  std::string_view name() const override { return "globe-reference"; }
  FrameStats draw(const ViewSetup& view, const RenderSettings& settings) override;

  std::size_t chunkCount() const { return chunks_.size(); }
  std::uint64_t triangleCount() const { return triangles_; }
  // The highest and lowest vertex above the ellipsoid (for near/far and camera paths), metres.
  double highestM() const { return highestM_; }
  double lowestM() const { return lowestM_; }

 private:
  struct Chunk {
    gl::Buffer vertices;
    gl::VertexArray vertexArray;
    const gl::Buffer* indices = nullptr;
    int vertsX = 0, vertsY = 0;
    Aabb ecefBounds;
  };

  void drawChunks(const gl::Program& program, const ViewSetup& view, FrameStats* stats);

  std::vector<Chunk> chunks_;
  GridIndexBuffers indexBuffers_;
  gl::Program fill_, wire_;
  std::optional<GlobeSky> sky_;
  gl::Texture drape_;
  glm::vec4 drapeBox_{0.0f};  // west, north, east - west, south - north (degrees)
  std::uint64_t triangles_ = 0;
  double highestM_ = 0.0, lowestM_ = 0.0;
  float cellM_ = 1.0f;  // a grid cell's side on the ground, metres
};

}  // namespace tellus
