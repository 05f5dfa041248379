#pragma once
// RINGO (seed 002, `--algo ringo`): nested rings of blocks around the viewer on the WGS84
// ellipsoid, drawn from static GPU buffers (the seed's "retained mode"). The GL-free parts are
// in src/tellus/lod/ringo/: the layout, the toroidal matrix and its reorganisation plan, the
// blocks' heights and meshes, and the reorganiser that rebuilds blocks on oneTBB workers.
//
// Per frame, on the render thread: the seed's list (where the viewer is, its height above the
// ground, the matrix's depth) and, when the viewer has crossed into another central block, one
// recentre() handed to the reorganiser; then at most `uploadsPerFrame` finished blocks become
// GPU buffers, and each block in the frustum is drawn with its coarser-edge mask (crack-free
// joins); positions are formed relative to the eye on the GPU, exactly. Blocks waiting for a replacement keep drawing; when
// the depth changes, the previous matrix's blocks draw until the new one is complete. Needs a
// current GL 4.5 context for its whole life.
#include <memory>
#include <optional>
#include <vector>

#include "tellus/dem/geoid.hpp"
#include "tellus/gl/buffer.hpp"
#include "tellus/gl/program.hpp"
#include "tellus/gl/vertex_array.hpp"
#include "tellus/lod/ringo/ringo_block_matrix.hpp"
#include "tellus/lod/ringo/ringo_reorganiser.hpp"
#include "tellus/render/globe/globe_shading.hpp"
#include "tellus/render/grid_index_buffers.hpp"
#include "tellus/render/terrain_renderer.hpp"
#include "tellus/tiles/global_store.hpp"

namespace tellus {

struct RingoOptions {
  int rings = 4;             // around the central 3 x 3 blocks (the seed's test: 4)
  int uploadsPerFrame = 16;  // finished blocks made GPU buffers per frame
  bool waitForBlocks = false;  // stills and tests: every frame waits until its matrix is complete
  const Geoid* geoid = nullptr;  // heights above the geoid made ellipsoidal (null: as stored)
};

// What the last frames did, for the harness and the viewer.
struct RingoFrameInfo {
  int depth = 0;              // the matrix's depth
  int blocksDrawn = 0;
  int blocksResident = 0;     // slots with a GPU buffer
  int uploads = 0;            // this frame
  bool reorganising = false;  // the reorganiser has work in flight
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

  const RingoFrameInfo& frameInfo() const { return info_; }
  const RingoLayout& layout() const { return layout_; }
  // The ground under (lat, lon) from the central block, NaN before it has arrived: metres
  // above the ellipsoid (with the geoid) or as stored.
  double groundUnderM(double latDeg, double lonDeg) const;
  // The same from the store's deepest tile there (one tile read): before the first matrix.
  double storeGroundM(double latDeg, double lonDeg) const;

 private:
  struct GpuBlock {
    RingoBlock block;
    Aabb bounds;  // ECEF
    int cells = 0;
    gl::Buffer vertices;
    gl::VertexArray vertexArray;
    const gl::Buffer* indices = nullptr;
    std::vector<float> heights;  // for the ground under the viewer
  };
  struct Matrix {
    std::optional<RingoBlockMatrix> blocks;
    std::unique_ptr<RingoReorganiser> reorganiser;
    std::vector<GpuBlock> slots;  // what is drawn, per slot
  };

  RingoRenderer() = default;
  void startMatrix(int depth, const GeoTileKey& centre);
  void upload(Matrix& matrix, RingoReadyBlock ready);
  bool complete(const Matrix& matrix) const;
  void drawMatrix(const Matrix& matrix, const gl::Program& program, const ViewSetup& view,
                  FrameStats* stats);

  std::shared_ptr<const GlobalStore> store_;
  RingoOptions options_;
  RingoLayout layout_;
  Matrix current_, previous_;
  GridIndexBuffers indexBuffers_;
  gl::Program fill_, wire_;
  std::optional<GlobeSky> sky_;
  RingoFrameInfo info_;
};

}  // namespace tellus
