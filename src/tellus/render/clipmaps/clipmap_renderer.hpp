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
// Two texture arrays take turns, one a frame: each is brought from the windows it held two
// frames ago to this frame's, and the other keeps the previous frame's windows, so the popping
// metric can redraw the previous frame exactly (drawPreviousSelection). prepare() updates the
// texture (FrameStats::textureUpdateMs) and culls the footprints against the frustum.
// Needs a current GL 4.5 context for its whole life.
#include <array>
#include <memory>
#include <string>
#include <vector>

#include "tellus/core/result.hpp"
#include "tellus/gl/buffer.hpp"
#include "tellus/gl/program.hpp"
#include "tellus/gl/texture.hpp"
#include "tellus/gl/vertex_array.hpp"
#include "tellus/lod/clipmaps/clipmap_layout.hpp"
#include "tellus/render/clipmaps/clipmap_store_levels.hpp"
#include "tellus/render/terrain_renderer.hpp"
#include "tellus/tiles/tile_store.hpp"

namespace tellus {

struct ClipmapOptions {
  std::string name = "clipmaps";
  int n = 255;     // vertices a level side, 2^k - 1
  int levels = 0;  // 0: enough for the coarsest to span twice the terrain
  float transitionWidth = 0.0f;  // level units; 0: n / 5 (at most (n + 1) / 4 - 3.5)
  bool culling = true;
  std::size_t cacheBytes = std::size_t(128) << 20;  // decoded tiles kept on the CPU
};

class ClipmapRenderer final : public TerrainRenderer {
 public:
  static Result<std::unique_ptr<ClipmapRenderer>> create(std::shared_ptr<const TileStore> store,
                                                         const ClipmapOptions& options);

  std::string_view name() const override { return options_.name; }
  void prepare(const ViewSetup& view, const RenderSettings& settings) override;
  FrameStats draw(const ViewSetup& view, const RenderSettings& settings) override;
  bool drawPreviousSelection(const ViewSetup& view, const RenderSettings& settings) override;
  std::vector<std::string> frameReport() const override;

  const clipmaps::ClipmapShape& shape() const { return shape_; }
  const clipmaps::Footprints& footprints() const { return footprints_; }
  ClipmapStoreLevels& levels() { return *levels_; }
  // The viewer (full-resolution (col, row)) and level origins of the last prepared frame.
  glm::dvec2 viewer() const { return frames_[std::size_t(current_)].viewer; }
  const std::vector<glm::ivec2>& origins() const { return frames_[std::size_t(current_)].origins; }
  // Samples uploaded by the last prepare().
  std::uint64_t lastUploadSamples() const { return lastUploadSamples_; }
  // Reads level `level`'s texture back (n + 1)^2 texels of (z_f, z_c), row-major by texel (tests).
  std::vector<glm::vec2> readLevel(int level) const;

 private:
  struct FrameState {  // one texture array's windows, and what a frame drew from it
    gl::Texture heights;  // RG32F, (n + 1)^2 x levels
    std::vector<glm::ivec2> origins;
    bool filled = false;
    glm::dvec2 viewer{0.0};
    std::vector<std::pair<int, const clipmaps::Piece*>> drawList;  // (level, piece)
    std::uint64_t triangles = 0;
  };

  ClipmapRenderer() = default;
  // Brings `state`'s texture to `origins`; returns the samples uploaded.
  std::uint64_t updateTexture(FrameState& state, const std::vector<glm::ivec2>& origins);
  void uploadRect(FrameState& state, int level, const clipmaps::SampleRect& rect);
  void cull(FrameState& state, const ViewSetup& view, float exaggeration) const;
  void drawFrame(const FrameState& state, const ViewSetup& view, const RenderSettings& settings);

  ClipmapOptions options_;
  std::shared_ptr<const TileStore> store_;
  std::unique_ptr<ClipmapStoreLevels> levels_;
  clipmaps::ClipmapShape shape_;
  clipmaps::Footprints footprints_;
  int gridWidth_ = 0, gridHeight_ = 0;
  double spacingXM_ = 1.0, spacingYM_ = 1.0;
  float minHeightM_ = 0.0f, maxHeightM_ = 0.0f;
  std::vector<float> levelErrorM_;
  gl::Buffer indexBuffer_;
  gl::VertexArray vertexArray_;
  gl::Program fill_, wire_;
  std::array<FrameState, 2> frames_;
  int current_ = 0;  // frames_[current_]: the last prepared frame
  int prepared_ = 0;
  bool preparedThisFrame_ = false;
  double lastUpdateMs_ = 0.0;
  std::uint64_t lastUploadSamples_ = 0;
  std::vector<glm::vec2> staging_;
};

}  // namespace tellus
