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
//
// From a global store (create(store, ...)) it draws, each frame, the cut of the store's quadtree
// that globe_store_cut.hpp chooses for the view: the store's finest tiles wherever their
// difference from a shallower tile would show, shallower tiles only where their error projects
// under the tolerance (1 px by default: a bound on a whole tile's largest error seen from its
// nearest point, so the error measured per pixel is far smaller, 0.03 px p99 on the steep
// descent). Each tile is one mesh of its (cells + 1)^2 samples
// (readGlobalTileSurface: the store's rule on shared edges) with a skirt that hides the
// T-junctions between tiles of different depths. Meshes are made in prepare() when a tile is
// first needed, on every core, and uploaded by the render thread (a reference waits for its
// data; it never waits for the GPU); they are dropped when two frames pass without them.
#include <cstdint>
#include <map>
#include <memory>
#include <optional>
#include <utility>
#include <vector>

#include "tellus/core/aabb.hpp"
#include "tellus/dem/drape_image.hpp"
#include "tellus/dem/geoid.hpp"
#include "tellus/dem/height_grid.hpp"
#include "tellus/gl/buffer.hpp"
#include "tellus/gl/program.hpp"
#include "tellus/gl/texture.hpp"
#include "tellus/gl/vertex_array.hpp"
#include "tellus/lod/globe/globe_mesh.hpp"
#include "tellus/render/globe/globe_shading.hpp"
#include "tellus/render/drawing/grid_index_buffers.hpp"
#include "tellus/render/terrain_renderer.hpp"
#include "tellus/tiles/global_store.hpp"

namespace tellus {

class GlobeReferenceRenderer final : public TerrainRenderer {
 public:
  static constexpr int kChunkQuads = 256;

  // `geoid` may be null: heights are then taken as ellipsoidal. `drape` (may be null): a colour
  // map drawn instead of the hypsometric tint (uploaded; not kept). Errors: a DEM that is not in
  // latitude/longitude, shaders that do not build.
  static Result<GlobeReferenceRenderer> create(const HeightGrid& grid, const Geoid* geoid,
                                               const DrapeImage* drape = nullptr);
  // Draws a global store: the cut of its tiles within `tolerancePx` of its finest data on
  // screen, chosen per frame. `geoid`, `drape` as above. Errors: shaders that do not build.
  static Result<GlobeReferenceRenderer> create(std::shared_ptr<const GlobalStore> store,
                                               const Geoid* geoid, const DrapeImage* drape,
                                               double tolerancePx);
  static constexpr double kDefaultStoreTolerancePx = 1.0;

  std::string_view name() const override { return "globe-reference"; }
  void prepare(const ViewSetup& view, const RenderSettings& settings) override;
  FrameStats draw(const ViewSetup& view, const RenderSettings& settings) override;
  bool drawPreviousSelection(const ViewSetup& view, const RenderSettings& settings) override;
  std::optional<Error> dataError() const override { return dataError_; }
  std::vector<std::string> frameReport() const override;

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
    float cellM = 1.0f;  // a grid cell's side on the ground, metres (wire.frag's fading)
  };
  struct StoreTile {  // a tile of the store's cut, as drawn
    std::vector<Chunk> chunks;
    std::uint64_t lastFrame = 0;  // the frame that last drew it
  };

  struct TileMesh {  // a store tile's mesh before upload (GL-free: made on any thread)
    globe::GlobeMesh mesh;
    float cellM = 1.0f;
  };

  Status initialise(const DrapeImage* drape);
  Chunk upload(globe::GlobeChunk& source, float cellM);
  Result<TileMesh> makeTileMesh(GeoTileKey key) const;
  void drawChunks(const gl::Program& program, const ViewSetup& view,
                  const std::vector<const Chunk*>& chunks, FrameStats* stats);
  void drawFrame(const ViewSetup& view, const RenderSettings& settings,
                 const std::vector<const Chunk*>& chunks, FrameStats* stats);

  std::vector<Chunk> chunks_;  // from a grid: all of them, made once
  // From a store: the tiles resident, those this frame draws and those the frame before drew.
  std::shared_ptr<const GlobalStore> store_;
  const Geoid* geoid_ = nullptr;
  double tolerancePx_ = kDefaultStoreTolerancePx;
  std::map<GeoTileKey, StoreTile> storeTiles_;
  std::vector<const Chunk*> drawn_, previous_;
  std::uint64_t frame_ = 0;
  std::size_t cutTiles_ = 0, cutCapped_ = 0, tilesMade_ = 0;
  std::pair<int, int> cutDepths_{0, 0};  // the shallowest and deepest tile of the cut
  double cutWorstPx_ = 0.0;
  std::optional<Error> dataError_;
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
