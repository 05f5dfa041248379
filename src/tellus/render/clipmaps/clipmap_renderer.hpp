#pragma once
// GPU geometry clipmaps (seed 004 section 2.3; Asirvatham & Hoppe 2005): the levels, footprints
// and geomorph of lod/clipmaps/, drawn from one index buffer over an n x n vertex grid whose
// vertices the vertex shader places from gl_VertexID, the level's origin and its heights.
//
// Heights live in an RG32F texture array, one n + 1 square layer per level, addressed
// toroidally (texel = sample mod (n + 1)): when the viewer moves, only the samples a level's
// window gains are read from the tile store (through a CPU tile cache) and uploaded, an L of
// rows and columns cut where it wraps. Texel = (z_f, z_c): the level's height and the coarser
// level's surface there; the vertex shader blends them in the transition band at each level's
// border (geomorphing) and the fragment shader blends the two levels' normals the same way.
//
// Off the render thread: the texels of an update are read and computed by a worker task
// (lod/clipmaps/clipmap_update.hpp); the render thread only uploads them once they are ready,
// a frame or more later, and meanwhile draws the windows the texture holds, with the viewer
// they were placed for (so every level's transition band still ends at its border: no crack).
// An update is placed for where the viewer will be when it lands (its last frame's velocity).
// Only the first frame, and a frame after a jump (the finest window more than a block away from
// where the viewer wants it), update on the render thread.
//
// Two texture arrays take turns: an update goes into the one not drawn, and the frame it lands
// in draws it, so the texture the previous frame drew is untouched and the popping metric can
// redraw the previous frame exactly (drawPreviousSelection). prepare() lands a ready update
// (FrameStats::textureUpdateMs: the render thread's part), culls the footprints against the
// frustum and starts the next update when the view has moved on. Needs a current GL 4.5 context
// for its whole life.
#include <array>
#include <atomic>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "tellus/core/result.hpp"
#include "tellus/gl/buffer.hpp"
#include "tellus/gl/program.hpp"
#include "tellus/gl/texture.hpp"
#include "tellus/gl/vertex_array.hpp"
#include "tellus/lod/clipmaps/clipmap_layout.hpp"
#include "tellus/lod/clipmaps/clipmap_update.hpp"
#include "tellus/render/clipmaps/clipmap_store_levels.hpp"
#include "tellus/render/clipmaps/clipmap_texel_staging.hpp"
#include "tellus/render/drawing/background_job.hpp"
#include "tellus/render/terrain_renderer.hpp"
#include "tellus/tiles/tile_store.hpp"

namespace tellus {

struct ClipmapOptions {
  std::string name = "clipmaps";
  int n = 303;     // vertices a level side, 4m - 1 (303: SSE p99 under 1 px on the Korea flyover, docs/clipmaps.md)
  int levels = 0;  // 0: enough for the coarsest to span twice the terrain
  float transitionWidth = 0.0f;  // level units; 0: n / 5 (at most (n + 1) / 4 - 3.5)
  bool culling = true;
  // Levels above the finest prefiltered by least squares (clipmap_prefilter.hpp); false: the
  // store's subsampled levels, as the papers draw them.
  bool prefilter = true;
  std::size_t cacheBytes = std::size_t(128) << 20;  // decoded tiles kept on the CPU
};

class ClipmapRenderer final : public TerrainRenderer {
 public:
  static Result<std::unique_ptr<ClipmapRenderer>> create(std::shared_ptr<const TileStore> store,
                                                         const ClipmapOptions& options);

  std::string_view name() const override { return options_.name; }
  void prepare(const ViewSetup& view, const RenderSettings& settings) override;
  FrameStats draw(const ViewSetup& view, const RenderSettings& settings) override;
  std::optional<Error> dataError() const override { return dataError_; }
  bool drawPreviousSelection(const ViewSetup& view, const RenderSettings& settings) override;
  std::vector<std::string> frameReport() const override;

  const clipmaps::ClipmapShape& shape() const { return shape_; }
  // What the levels' heights are made of: texels hold texelHeights() of
  // clipmaps::filteredSampler(store levels, levelFilter()).
  clipmaps::LevelFilter levelFilter() const {
    return {options_.prefilter, minHeightM_, maxHeightM_, glm::ivec2(gridWidth_, gridHeight_)};
  }
  const clipmaps::Footprints& footprints() const { return footprints_; }
  // The heights' reader; not while an update is in flight (its worker reads them): call
  // finishUpdate() first (tests).
  ClipmapStoreLevels& levels() { return *levels_; }
  // The viewer (full-resolution (col, row)) and level origins of the last prepared frame.
  glm::dvec2 viewer() const { return frame_.viewer; }
  const std::vector<glm::ivec2>& origins() const { return frame_.origins; }
  // Samples uploaded by the last prepare().
  std::uint64_t lastUploadSamples() const { return lastUploadSamples_; }
  // Worker updates landed so far, and how many of them the GPU copied from a staging slot.
  std::uint64_t workerUpdates() const { return workerUpdates_; }
  std::uint64_t stagedUpdates() const { return stagedUpdates_; }
  // Waits for the update in flight, if any (tests: the next prepare() lands it).
  void finishUpdate();
  // Reads level `level`'s texture back (n + 1)^2 texels of (z_f, z_c), row-major by texel, of
  // the texture the last frame drew (tests).
  std::vector<glm::vec2> readLevel(int level) const;

  ~ClipmapRenderer() override;

 private:
  struct HeightTexture {
    gl::Texture heights;  // RG32F, (n + 1)^2 x levels
    std::vector<glm::ivec2> origins;  // the windows it holds
    glm::dvec2 viewer{0.0};           // the viewer they were placed for
    bool filled = false;
  };
  struct DrawnFrame {  // what a frame drew
    int texture = -1;
    std::vector<glm::ivec2> origins;
    glm::dvec2 viewer{0.0};
    std::vector<std::pair<int, const clipmaps::Piece*>> drawList;  // (level, piece)
    std::uint64_t triangles = 0;
  };
  // What a worker's update job hands back.
  struct UpdateResult {
    clipmaps::ClipmapUpdate update;
    std::optional<Error> error;  // the store's first failed read, if any
    bool staged = false;         // its texels are in staging slot updateSlot_, not in update
  };

  ClipmapRenderer() = default;
  clipmaps::ClipmapUpdate buildUpdate(const std::vector<glm::ivec2>* from, glm::dvec2 viewer);
  // The direct upload (glTextureSubImage3D of the update's texels, on the render thread): the
  // first fill, jumps, and the reference the staged GPU copy is tested against.
  void upload(HeightTexture& texture, const clipmaps::ClipmapUpdate& update);
  // Records that `texture` now holds `update`'s windows (its texels uploaded or being copied).
  static void holdWindows(HeightTexture& texture, const clipmaps::ClipmapUpdate& update);
  void releaseUpdateSlot();
  void startUpdate(int texture, glm::dvec2 viewer);
  // Uploads the finished update into its texture; returns that texture.
  int landUpdate();
  // The finest level's window lags too far behind `wanted` to wait for a worker.
  bool farBehind(const std::vector<glm::ivec2>& wanted, const std::vector<glm::ivec2>& held) const;
  void cull(DrawnFrame& frame, const ViewSetup& view, float exaggeration) const;
  void drawFrame(const DrawnFrame& frame, const ViewSetup& view, const RenderSettings& settings);

  ClipmapOptions options_;
  std::shared_ptr<const TileStore> store_;
  std::unique_ptr<ClipmapStoreLevels> levels_;
  clipmaps::ClipmapShape shape_;
  clipmaps::Footprints footprints_;
  int gridWidth_ = 0, gridHeight_ = 0;
  double spacingXM_ = 1.0, spacingYM_ = 1.0;
  float minHeightM_ = 0.0f, maxHeightM_ = 0.0f;
  // The screen-space error shading's data: every level's tiles' geometric errors (R32F, a layer
  // a level, row 0 north) and, per level, its tile counts and the full-resolution samples a
  // tile spans.
  gl::Texture tileErrors_;
  std::vector<glm::ivec2> errorTiles_;
  std::vector<float> errorSpanSamples_;
  gl::Buffer indexBuffer_;
  gl::VertexArray vertexArray_;
  gl::Program fill_, wire_;
  std::array<HeightTexture, 2> textures_;
  DrawnFrame frame_, previousFrame_;  // the last prepared frame and the one before
  int prepared_ = 0;
  bool preparedThisFrame_ = false;
  double lastUpdateMs_ = 0.0;
  std::uint64_t lastUploadSamples_ = 0;
  double unreportedWorkerCpuMs_ = 0.0;
  std::uint64_t jumps_ = 0;
  std::uint64_t workerUpdates_ = 0, stagedUpdates_ = 0;
  glm::dvec2 lastViewer_{0.0};  // the viewer of the last prepare() (its velocity predicts)
  bool hasLastViewer_ = false;  // updates made on the render thread after a jump
  std::optional<Error> dataError_;
  int updateTexture_ = 0;                           // the texture the update in flight is for
  std::unique_ptr<ClipmapTexelStaging> staging_;    // where workers stage texels for the GPU's copy
  int updateSlot_ = -1;                             // the staging slot the update in flight holds
  // Last: destroyed first, so a job in flight ends before what it writes to.
  BackgroundJob<UpdateResult> update_{"clipmaps"};  // the update a worker is building
};

}  // namespace tellus
