#pragma once
// The rings renderer of seed 000 (`--algo rings`): concentric rings of patches around the
// viewer, static patch meshes displaced on the GPU, GPU stitching, frustum culling with the
// tiles' height bounds, and an out-of-core GPU tile cache.
//
// - A patch is the footprint of one level-0 tile of the store (tileSize cells). The patch at
//   Chebyshev distance d from the centre patch has level of detail lod(d) (RingsStructure): its
//   mesh has patchCells >> lod cells per side and reads pyramid level lod + log2(tileSize /
//   patchCells) (capped at the coarsest), so ring after ring the data coarsens with the mesh.
// - Heights reach the GPU through TileResidency: a texture array of `gpuSlots` tiles (the
//   seed's 40-entry cache by default), LRU with last-use frames, filled from a CPU TileCache
//   whose loads run on worker threads (at most maxUploadsPerFrame uploads per frame). The
//   coarsest tile is loaded at creation and pinned, so a patch whose tiles are not resident yet
//   draws from its finest resident ancestor: coarser, never a hole.
// - Stitching happens in the vertex shader (shaders/rings/rings.vert): odd vertices of edges
//   facing a coarser ring collapse onto even ones (the seed's orientation x edge look-up), and
//   edge vertices read the coarser data level of the two patches sharing the edge, so the mesh
//   stays crack-free while tiles stream in. This holds exactly when tiles of one level agree on
//   their shared border samples, as lossless stores (raw, zstd) do; lossy codecs (bounded, lerc)
//   code each tile on its own and may leave height steps of up to twice their error there.
// - Positions are formed camera-relative from integer sample differences: no jitter far from
//   the origin, bit-identical shared vertices.
//
// Needs a current GL 4.5 context for its whole life.
#include <array>
#include <cstddef>
#include <functional>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "tellus/gl/buffer.hpp"
#include "tellus/gl/program.hpp"
#include "tellus/gl/texture.hpp"
#include "tellus/gl/vertex_array.hpp"
#include "tellus/lod/rings/rings_structure.hpp"
#include "tellus/lod/rings/tile_residency.hpp"
#include "tellus/render/fractal/fractal_gpu_decoder.hpp"
#include "tellus/render/terrain_renderer.hpp"
#include "tellus/tiles/tile_cache.hpp"

namespace tellus {

struct RingsOptions {
  std::string name = "rings";  // what name() reports (the registry names the variants)
  // Mesh cells per side of a finest patch: 0 = the tile size (a vertex per sample near the
  // viewer); the seed used 128 for its 256-sample tiles (a vertex per 2x2 samples).
  int patchCells = 0;
  int rings = 0;      // 0: enough rings to reach the whole terrain from any patch
  int gpuSlots = 40;  // texture-array slots (seed 000's cache of 40 entries)
  bool frustumCulling = true;
  bool bruteForce = false;  // every patch at the finest level of detail (no rings)
  // Load every missing tile a frame needs before drawing it (stills, deterministic tests)
  // instead of streaming them in over the next frames.
  bool waitForTiles = false;
  int maxUploadsPerFrame = 16;  // GPU uploads per frame when streaming
  std::size_t cpuCacheBytes = std::size_t(256) << 20;
  // Tiles for which this returns false are never loaded (tests: a tile that never arrives).
  std::function<bool(TileKey)> tileFilter;
  // Seed 000's "Base incremental" (fractal stores only): tiles arrive as fractal codes and are
  // decoded on the GPU, each with as many iterations as its nearest patch needs (the full
  // count, residual included, at the finest level of detail, one fewer per level beyond, at
  // least one); a tile keeps iterating from where it stopped as the viewer approaches.
  bool incrementalFractal = false;
};

// What the last prepare() decided, for tests and diagnostics.
struct RingsFrameInfo {
  int centreX = 0, centreY = 0;  // centre patch
  int slotsRefilled = 0;         // ring-structure slots updateRings refilled this frame
  int viewerHeight = 0;          // viewer height above the centre patch, patch widths
  int windowPatches = 0;         // patches of the rings window inside the terrain
  int visiblePatches = 0;        // of which drawn (after culling)
  int fallbackPatches = 0;       // drawn from a coarser level than they want (tiles missing)
  std::array<int, 16> patchesPerLod{};
  int tilesWanted = 0;        // distinct tiles the visible patches need (with ancestors)
  int misses = 0;             // of which not resident in the GPU cache at request time
  int uploads = 0;            // tiles uploaded for this frame
  int fractalIterations = 0;  // GPU fractal iterations run this frame (incremental decoding)
};

class RingsRenderer final : public TerrainRenderer {
 public:
  static Result<std::unique_ptr<RingsRenderer>> create(std::shared_ptr<const TileStore> store,
                                                       RingsOptions options = {});
  ~RingsRenderer() override;

  std::string_view name() const override { return options_.name; }
  void prepare(const ViewSetup& view, const RenderSettings& settings) override;
  FrameStats draw(const ViewSetup& view, const RenderSettings& settings) override;
  // The previous prepare()'s patches with the data levels they read then; patches whose tiles
  // have been evicted since are left out. (Incremental fractal decoding: the tiles' current
  // iterations.)
  bool drawPreviousSelection(const ViewSetup& view, const RenderSettings& settings) override;
  std::vector<std::string> frameReport() const override;

  const RingsFrameInfo& lastFrame() const { return frame_; }
  const TileResidency& residency() const { return residency_; }
  const RingsStructure& rings() const { return structure_; }
  int patchesX() const { return patchesX_; }
  int patchesY() const { return patchesY_; }
  // Level of detail -> pyramid level its patches want.
  int wantedLevel(int lod) const;
  // Incremental fractal decoding: the GPU iterations `key`'s tile has had, -1 when it is not
  // resident (or the renderer does not decode incrementally).
  int fractalIterationsOf(TileKey key) const;
  // ... and the full count its code was made for (-1 likewise).
  int fractalFullIterationsOf(TileKey key) const;

 private:
  struct VisiblePatch {
    int x = 0, y = 0, lod = 0, distance = 0;
    PatchOrientation orientation = PatchOrientation::Centre;
    bool coarserOutside = false;
  };
  struct PatchInstance {  // matches rings.vert's aPatch
    std::int32_t x = 0, y = 0;
    std::int32_t lodInfo = 0;
    std::int32_t levels = 0;
  };
  struct LodMesh {
    int cells = 0;
    std::uint64_t triangles = 0;
    gl::Buffer vertices, indices;
  };
  struct PendingUpload {
    int slot = 0;
    TileHandle tile;
  };
  struct WantedTile {
    TileKey key;
    int distance = 0;
    int lod = 0;  // finest level of detail of the patches that want it
  };

  RingsRenderer() = default;
  void moveCentreTo(int x, int y);
  Aabb patchBox(int x, int y, const glm::dvec3& camera, float exaggeration) const;
  void requestTiles();
  void loadTiles();
  int lodOfNeighbour(int x, int y) const;
  void buildInstances();
  // Incremental fractal decoding: note that `slot` serves a patch at `lod` this frame.
  void wantIterationsFor(int slot, int lod);
  // Loads arrived fractal codes and iterates every slot up to what its patches need.
  void decodeFractalTiles();
  void drawPass(const gl::Program& program, bool wire, const std::vector<int>& lodFirstInstance,
                FrameStats* stats);
  // Uploads `instances` (grouped by level of detail, lodFirstInstance[lod] the first of each,
  // one past the end last) and draws them from `view`.
  FrameStats drawInstances(const ViewSetup& view, const RenderSettings& settings,
                           const std::vector<PatchInstance>& instances,
                           const std::vector<int>& lodFirstInstance);
  // Whether every tile `instance` reads is still resident.
  bool instanceIsResident(const PatchInstance& instance) const;
  // Uniforms that depend only on the store and the residency layout: set once.
  void setConstantUniforms();
  // World (x, y) as level-0 sample coordinates (col east, row south), fractional.
  std::pair<double, double> sampleCoordinates(const glm::dvec3& world) const;

  RingsOptions options_;
  std::shared_ptr<const TileStore> store_;
  std::unique_ptr<TileCache> cache_;
  RingsStructure structure_;
  TileResidency residency_;
  int tileSize_ = 0, patchesX_ = 0, patchesY_ = 0, levelShift_ = 0, maxLod_ = 0;
  int dataWidth_ = 0, dataHeight_ = 0;
  double spacingXM_ = 1.0, spacingYM_ = 1.0;
  std::vector<float> patchMinM_, patchMaxM_;  // per patch, from the level-0 tiles' stats

  gl::Program fill_, wire_;
  gl::VertexArray vertexArray_;
  std::vector<LodMesh> meshes_;  // per level of detail
  gl::Texture heights_;          // texture array, one tile per layer
  gl::Buffer pageTable_;         // SSBO mirror of residency_.pageTable()
  gl::Buffer instanceBuffer_;
  std::vector<float> slotErrorM_;  // per slot: its tile's geometric error, metres
  gl::Buffer slotErrorBuffer_;     // SSBO mirror of slotErrorM_
  std::unique_ptr<FractalGpuDecoder> fractalDecoder_;  // incremental fractal decoding only
  std::vector<int> slotLod_;  // per slot: finest lod served this frame (incremental decoding)

  // Per frame.
  RingsFrameInfo frame_;
  std::vector<VisiblePatch> visible_;
  std::vector<WantedTile> wanted_;
  std::vector<PendingUpload> pending_;
  std::vector<std::vector<PatchInstance>> instancesByLod_;
  std::vector<PatchInstance> instances_;  // concatenated by level of detail
  std::vector<int> lodFirstInstance_;
  std::vector<PatchInstance> previousInstances_;  // the frame before's, for the popping metric
  std::vector<int> previousLodFirstInstance_;
  double reportedWorkerCpuSeconds_ = 0.0;  // the cache's worker CPU at the last draw()
  bool reportedLoadError_ = false;
};

}  // namespace tellus
