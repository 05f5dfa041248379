#pragma once
// RINGO (seed 002, `--algo ringo`): nested rings of blocks around the viewer on the WGS84
// ellipsoid, drawn from static GPU buffers (the seed's "retained mode"). The GL-free parts are
// in src/tellus/lod/ringo/: the layout, the toroidal matrix and its reorganisation plan, the
// blocks' heights and meshes, and the reorganiser that rebuilds blocks on oneTBB workers.
//
// Per frame, on the render thread: the seed's list (where the viewer is, its height above the
// ground, the matrix's depth) and, when the viewer has crossed into another central block, one
// recentre() handed to the reorganiser; then finished blocks are handed to worker tasks that
// copy them into persistently mapped GPU buffers (`uploadKiBPerFrame` a frame; a block is drawn
// once its copy has ended), and each block in the frustum is drawn with its coarser-edge mask (crack-free
// joins); positions are formed relative to the eye on the GPU, exactly. Blocks waiting for a
// replacement keep drawing; when the depth changes, the previous matrix's blocks draw until the
// new one is complete, and an abandoned matrix's reorganiser finishes its running move in the
// background (the render thread never waits for it). Needs a current GL 4.5 context for its
// whole life.
#include <atomic>
#include <deque>
#include <limits>
#include <map>
#include <memory>
#include <optional>
#include <span>
#include <vector>

#include <tbb/task_group.h>

#include "tellus/dem/geoid.hpp"
#include "tellus/gl/buffer.hpp"
#include "tellus/gl/program.hpp"
#include "tellus/gl/vertex_array.hpp"
#include "tellus/lod/ringo/ringo_block_matrix.hpp"
#include "tellus/lod/ringo/ringo_reorganiser.hpp"
#include "tellus/render/globe/globe_shading.hpp"
#include "tellus/render/ringo/ringo_block_buffers.hpp"
#include "tellus/render/drawing/grid_index_buffers.hpp"
#include "tellus/render/terrain_renderer.hpp"
#include "tellus/tiles/global_store.hpp"

namespace tellus {

// The renderer's default layout (issue 45): blocks a tenth of the distance to the horizon with 8
// rings reach about as far as the seed's fifth with 4 (9.5 against 5.5 blocks from the centre),
// draw the ground near the viewer twice as fine, and add about 10 % triangles (the outer rings
// are a few cells a block): the descent goes from SSE p99 1.76 to 0.42 px and popping
// p99 1.11 to 0.29 px (docs/ringo.md). The seed's own test is `--ringo-rings 4
// --ringo-blocks-to-horizon 5` (kRingoBlocksToHorizon, RingoLayout's default).
constexpr int kRingoDefaultRings = 8;
constexpr double kRingoDefaultBlocksToHorizon = 10.0;

struct RingoOptions {
  int rings = kRingoDefaultRings;  // around the central 3 x 3 blocks (the seed's test: 4)
  // Vertex data handed per frame to the workers that copy it into mapped GPU buffers, KiB (a
  // central block is 4.3 MiB, an outer ring's 19 KiB; a border crossing about 28 MiB, a whole
  // matrix of 4 rings 65.4 MiB): how fast a reorganisation reaches the GPU. The default takes a
  // new depth's whole matrix in one frame. The render thread copies nothing.
  int uploadKiBPerFrame = 81920;
  // The block size: the distance to the horizon over this many blocks (more: smaller, finer
  // blocks, a matrix that ends nearer).
  double blocksToHorizon = kRingoDefaultBlocksToHorizon;
  int threads = 0;  // reorganisation worker threads at most (0: every core)
  // Frames over which a new matrix morphs from the surface the previous depth's matrix drew to
  // its own (lod/ringo/ringo_morph.hpp; 0: it replaces it at once, a step).
  int morphFrames = 8;
  bool waitForBlocks = false;  // stills and tests: every frame waits until its matrix is complete
  const Geoid* geoid = nullptr;  // heights above the geoid made ellipsoidal (null: as stored)
};

// What the last frames did, for the harness and the viewer.
struct RingoFrameInfo {
  int depth = 0;              // the matrix's depth
  int blocksDrawn = 0;
  int blocksResident = 0;     // slots with a GPU buffer
  int uploads = 0;            // blocks whose GPU buffer was completed this frame
  std::size_t uploadBytes = 0;  // vertex bytes copied this frame
  bool reorganising = false;  // the reorganiser has work in flight
  float morphRemaining = 0.0f;  // of the drawn matrix's morph from the previous depth
  RingoReorganiserStats reorganiser;
};

class RingoRenderer final : public TerrainRenderer {
 public:
  // Errors: a store whose tiles do not have the layout's cells; shaders that do not build.
  static Result<std::unique_ptr<RingoRenderer>> create(std::shared_ptr<const GlobalStore> store,
                                                       RingoOptions options);
  ~RingoRenderer() override;

  std::string_view name() const override { return "ringo"; }
  void prepare(const ViewSetup& view, const RenderSettings& settings) override;
  FrameStats draw(const ViewSetup& view, const RenderSettings& settings) override;
  // The blocks the frame before the last drew (the buffers kept alive for it), with their
  // coarser-edge masks, culled against `view`.
  bool drawPreviousSelection(const ViewSetup& view, const RenderSettings& settings) override;
  std::vector<std::string> frameReport() const override;

  const RingoFrameInfo& frameInfo() const { return info_; }
  const RingoLayout& layout() const { return layout_; }
  // The ground under (lat, lon) as drawn by the block there (its triangles), NaN where no
  // block is drawn: metres above the ellipsoid (with the geoid) or as stored. The seed's
  // collision test: a camera kept above it never goes under the terrain RINGO draws.
  double groundUnderM(double latDeg, double lonDeg) const;
  double drawnGroundM(double latDeg, double lonDeg) const override {
    return groundUnderM(latDeg, lonDeg);
  }
  // The same from the store's deepest tile there (one tile read): before the first matrix.
  double storeGroundM(double latDeg, double lonDeg) const;

 private:
  struct GpuBlock {
    RingoBlock block;
    Aabb bounds;  // ECEF
    RingoBlockBuffers gpu;  // returned to the pool when the block goes
    // For the ground under the viewer and for the next matrix's morph (shared with its
    // RingoMorphSource): its heights and its vertices' morph deltas (null: none).
    std::shared_ptr<const std::vector<float>> heights;
    std::shared_ptr<const std::vector<float>> morphDeltas;
  };
  struct Matrix {
    std::optional<RingoBlockMatrix> blocks;
    std::unique_ptr<RingoReorganiser> reorganiser;
    std::vector<std::shared_ptr<const GpuBlock>> slots;  // what is drawn, per slot (or null)
    std::map<std::uint64_t, std::size_t> moveSizes;  // moves not yet shown: their update count
    // The morph from the previous depth's surface (null: none, or done): the share still to go
    // as last drawn, and whether a successor froze it there.
    std::shared_ptr<const RingoMorphSource> morphFrom;
    float morphRemaining = 0.0f;
    bool morphFrozen = false;
  };
  // A finished block whose vertices a worker copies into its mapped GPU buffer.
  struct PendingUpload {
    int generation = 0;  // the matrix it is for (matrixGeneration_)
    std::uint64_t move = 0;
    int slot = 0;
    bool failed = false;  // the block could not be loaded: the slot keeps what it has
    std::shared_ptr<GpuBlock> block;  // null: the slot empties
    std::vector<RingoVertex> vertices;  // to copy; freed by the worker
    std::atomic<bool> copied{false};
  };
  // A block as a frame draws it.
  struct DrawnBlock {
    std::shared_ptr<const GpuBlock> block;
    std::uint32_t coarserEdges = 0;
    float morphRemaining = 0.0f;  // its matrix's, that frame
  };

  RingoRenderer() = default;
  // Starts the matrix of `depth` around `centre`, its blocks morphing from `morphFrom`.
  void startMatrix(int depth, const GeoTileKey& centre,
                   std::shared_ptr<const RingoMorphSource> morphFrom);
  // The surface `drawn` shows now, for its successor to morph from (null: morphing is off);
  // `drawn`'s own morph stops where it is.
  std::shared_ptr<const RingoMorphSource> captureMorphSource(Matrix& drawn) const;
  // The matrix draw() draws: the current one once filled, else the previous depth's.
  Matrix& drawnMatrix();
  // Hands one move's updates to the matrix's reorganiser, noting its size.
  void submitMove(Matrix& matrix, std::vector<RingoBlockUpdate> updates);
  // Drops a matrix: its buffers at once, its reorganiser once its running move ends.
  void retire(Matrix& matrix);
  // Installs the moves whose blocks have all been copied into GPU buffers, then hands finished
  // blocks to copy tasks, `budgetBytes` of vertices this frame (all of them and waits, with
  // `wait`).
  void uploadReady(std::size_t budgetBytes, bool wait);
  // Installs every move, oldest first, whose blocks have all arrived and been copied.
  void installCopied();
  // The matrix has a block under (lat, lon): drawing it shows ground under the viewer.
  bool covers(const Matrix& matrix, double latDeg, double lonDeg) const;
  // Every slot that should hold a block holds one (perhaps still an older one): drawable.
  bool filled(const Matrix& matrix) const;
  // Every resident block of `matrix` with its coarser-edge mask: the edges whose neighbour, as
  // drawn, has fewer cells (during a reorganisation a block may still be the one from before).
  std::vector<DrawnBlock> selection(const Matrix& matrix) const;
  void drawBlocks(std::span<const DrawnBlock> blocks, const gl::Program& program,
                  const ViewSetup& view, FrameStats* stats);
  FrameStats drawSelection(std::span<const DrawnBlock> blocks, const ViewSetup& view,
                           const RenderSettings& settings);
  double workerCpuSeconds() const;  // reorganisers' and copies', since the renderer was made
  // The deepest depth, up to centre.depth, the store holds within the matrix's window around
  // `centre` (a tile of the depth wanted), cached for the last centre.
  int deepestStoredAround(const GeoTileKey& centre);

  std::shared_ptr<const GlobalStore> store_;
  RingoOptions options_;
  RingoLayout layout_;
  GridIndexBuffers indexBuffers_;
  std::optional<RingoBufferPool> pool_;  // before every block: outlives them
  Matrix current_, previous_;
  int matrixGeneration_ = 0;                          // bumped by startMatrix()
  std::deque<std::unique_ptr<PendingUpload>> copying_;  // in the order taken
  // The copies' tasks (a pointer: task_group's destructor may throw, a renderer's may not).
  std::unique_ptr<tbb::task_group> copies_ = std::make_unique<tbb::task_group>();
  std::atomic<std::int64_t> copyCpuNanoseconds_{0};  // the copies' CPU time
  // Reorganisers of abandoned matrices, finishing their running move.
  std::vector<std::unique_ptr<RingoReorganiser>> retiring_;
  double retiredWorkerCpuSeconds_ = 0.0;   // of the reorganisers destroyed
  double reportedWorkerCpuSeconds_ = 0.0;  // workerCpuSeconds() at the last draw()
  std::vector<DrawnBlock> lastDrawn_, drawnBefore_;  // the last two frames' selections
  gl::Program fill_, wire_;
  std::optional<GlobeSky> sky_;
  RingoFrameInfo info_;
  std::optional<std::pair<GeoTileKey, int>> deepestAround_;
  double lastGroundM_ = std::numeric_limits<double>::quiet_NaN();  // under the viewer
  double lastClearanceM_ = std::numeric_limits<double>::quiet_NaN();  // the last frame's
  double lastEyeHeightM_ = std::numeric_limits<double>::quiet_NaN();  // above the ellipsoid
  RingoLatLon lastEye_{std::numeric_limits<double>::quiet_NaN(),
                       std::numeric_limits<double>::quiet_NaN()};  // the last frame's, degrees
  double depthsMovedThisFrame_ = 0.0;  // |log4| of this frame's clearance over the last's
};

}  // namespace tellus
