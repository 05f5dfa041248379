#pragma once
// The spiral globe (seed 001, `--algo spiral`): one static exponential spiral, generated once
// into a vertex buffer, re-centred every frame on the focal point under the camera and wrapped
// in the vertex shader onto the chosen projection (globe, flat, hyperbolic, dome), its heights
// fetched from textures of the global store's surface (a stack of windows, one a depth, around
// the focal point). The drawn part is one index range of the strip, from a minimum radius (the
// central hole, filled by a fan) to a maximum (the last revolution), chosen by the seed's
// occlusion-query feedback or analytically from the camera; both are computed every frame and
// reported. The GL-free parts are in src/tellus/lod/spiral/. Needs a current GL 4.5 context for
// its whole life.
//
// Per frame, on the render thread: the focal point (snapped to the finest drawn depth's samples,
// so the mesh stands still between snaps), the radii (the queries of a frame before, read only
// when available: the GPU never waits), height windows that the focal point has strayed from
// handed to a worker to re-read (the vertex falls back to a coarser window meanwhile), finished
// windows uploaded; then three draws: the fan (counted), the strip without its last revolution,
// the last revolution (counted).
#include <array>
#include <filesystem>
#include <memory>
#include <optional>
#include <vector>

#include <tbb/task_group.h>

#include "tellus/dem/geoid.hpp"
#include "tellus/gl/buffer.hpp"
#include "tellus/gl/program.hpp"
#include "tellus/gl/query.hpp"
#include "tellus/gl/texture.hpp"
#include "tellus/gl/vertex_array.hpp"
#include "tellus/lod/spiral/spiral_height_levels.hpp"
#include "tellus/lod/spiral/spiral_mesh.hpp"
#include "tellus/lod/spiral/spiral_projection.hpp"
#include "tellus/lod/spiral/spiral_radius.hpp"
#include "tellus/render/globe/globe_shading.hpp"
#include "tellus/render/spiral/imagery_overlay.hpp"
#include "tellus/render/terrain_renderer.hpp"
#include "tellus/tiles/global_store.hpp"

namespace tellus {

enum class SpiralRadiusMode { Feedback, Analytic };

// The fragment shader's features (spiral.frag), each switchable for the seed's Table 3.
enum SpiralFeature : std::uint32_t {
  kSpiralClouds = 1,
  kSpiralNightLights = 2,
  kSpiralTangentNormalize = 4,
  kSpiralBumpMapping = 8,
  kSpiralSpecular = 16,
  kSpiralDiffuse = 32,
  kSpiralAllFeatures = 63,
};

struct SpiralOptions {
  // The seed's spiral parameters: spin between vertices (dividing 360), revolutions for the
  // radius to double, the innermost radius (radians of arc; 1e-7 is 0.64 m). Triangles are
  // about as long as wide when a revolution's growth matches the spin step: 2^(1/spinToDouble)
  // - 1 = 2 pi / n (n = 360 / spinStep), spinToDouble about 0.11 n: 10 for 4 degrees.
  double spinStepDeg = 4.0;
  double spinToDouble = 10.0;
  double baseRadiusRad = 1e-7;
  SpiralProjection projection = SpiralProjection::Globe;
  SpiralRadiusMode radiusMode = SpiralRadiusMode::Feedback;
  bool correctRadius = false;  // the seed's square-root radius correction
  // Each vertex's height blended between the two depths its spacing lies between, instead of
  // taken from one and switching at once as the radii change. Off by default: on the issue 45
  // descents it changes no popping (the sliding mesh's) and costs 8 % SSE (docs/spiral.md).
  bool blendDepths = false;
  double fanPixels = 256.0;    // the central fan's target, pixels
  // The Blue Marble folder (colour, altitude, clouds, night lights, water), converted once to
  // cube maps cached beside the store (STORE.spiral-textures/); empty: the hypsometric tint.
  std::filesystem::path texturesDir;
  int cubeFaceSize = 2048;
  std::uint32_t features = kSpiralAllFeatures;
  bool whiteShader = false;            // the seed's 'white' fragment shader (Table 1)
  double cloudDegreesPerFrame = 0.05;  // the clouds' drift eastwards
  bool waitForHeights = false; // stills and tests: every frame waits for its height windows
                               // (and the imagery settles: its counts read at once)
  // Georeferenced images draped as a second pass (a Landsat scene, decals), each preprocessed
  // once into an imagery pyramid cached beside the store (STORE.spiral-textures/NAME.timagery)
  // and drawn as a texture quadtree driven by occlusion queries; later images on top.
  std::vector<std::filesystem::path> imagery;
  ImageryOverlayOptions imageryOptions;
  const Geoid* geoid = nullptr;  // heights above the geoid made ellipsoidal (null: as stored)
};

// What the last frame did, for the harness, the viewer and the docs.
struct SpiralFrameInfo {
  double focusLatDeg = 0.0, focusLonDeg = 0.0;
  SpiralRadii radii;     // drawn
  SpiralRadii analytic;  // the analytic choice for the same camera (reported either way)
  SpiralRange range;
  std::uint64_t fanPixels = 0, outerPixels = 0;  // the last counts read (a frame or more late)
  bool countsRead = false;   // counts arrived this frame
  int finestDepth = 0;       // the finest height window wanted
  int windowsResident = 0;
  int windowMoves = 0;       // windows re-read and uploaded this frame
  ImageryFrameInfo imagery;  // the draped images' quadtrees (none: zeros)
};

class SpiralRenderer final : public TerrainRenderer {
 public:
  // Errors: bad spiral parameters, unreadable base heights, shaders that do not build.
  static Result<std::unique_ptr<SpiralRenderer>> create(std::shared_ptr<const GlobalStore> store,
                                                        SpiralOptions options);
  ~SpiralRenderer() override;

  std::string_view name() const override { return "spiral"; }
  void prepare(const ViewSetup& view, const RenderSettings& settings) override;
  FrameStats draw(const ViewSetup& view, const RenderSettings& settings) override;
  bool drawPreviousSelection(const ViewSetup& view, const RenderSettings& settings) override;
  std::vector<std::string> frameReport() const override;

  const SpiralFrameInfo& frameInfo() const { return info_; }
  const SpiralMesh& mesh() const { return mesh_; }
  // The draped images (null without --spiral-imagery).
  const ImageryOverlay* imagery() const { return imagery_.get(); }
  const SpiralOptions& options() const { return options_; }
  void setProjection(SpiralProjection projection) { options_.projection = projection; }
  // The ground under (lat, lon) as the height windows hold it (the finest holding it), metres
  // above the ellipsoid: what the camera keeps above.
  double groundM(double latDeg, double lonDeg) const;
  double drawnGroundM(double latDeg, double lonDeg) const override {
    return groundM(latDeg, lonDeg);
  }

  // For tests: the eye-relative positions the vertex shader gives the drawn range's vertices
  // (transform feedback), and the CPU twin's for the same frame (spiral_projection.hpp and
  // spiral_height_levels.hpp), in the same order: vertices range.first .. range.first +
  // range.count + n, then the centre.
  std::vector<glm::vec3> captureDrawnPositions(const ViewSetup& view);
  std::vector<glm::vec3> referenceDrawnPositions(const ViewSetup& view) const;

 private:
  static constexpr int kMaxLevels = 24;
  static constexpr int kSlots = 3;  // layers a depth: drawn, the frame before's, and a fresh one

  // One depth's window round the focal point.
  struct Level {
    std::shared_ptr<const SpiralHeightWindow> window;  // resident (null: none yet)
    int slot = 0;  // its texture layer is level * kSlots + slot
    // A re-read in flight (written by a worker, taken by the render thread once `done`).
    struct Pending {
      SpiralHeightWindow window;
      Status status;
      std::atomic<bool> done{false};
    };
    std::shared_ptr<Pending> pending;
  };
  // Everything a draw needs that the view does not give: kept for the frame before too.
  struct DrawState {
    bool valid = false;
    SpiralFocus focus;
    glm::dvec3 focusEcef{0.0};
    SpiralRadii radii;
    SpiralRange range;
    std::size_t fanOffset = 0;  // bytes into fanIndices_
    glm::vec2 baseFocal{0.0f};
    int levelCount = 0;
    std::array<int, kMaxLevels> layer{};
    std::array<glm::vec2, kMaxLevels> levelFocal{};
    std::array<float, kMaxLevels> levelStepRad{};
  };

  SpiralRenderer() = default;
  // The finest depth stored round (lat, lon) (the store's deepest at worst).
  int finestStoredAround(double latDeg, double lonDeg) const;
  // Starts re-reads of the windows the focal point has strayed from, installs finished ones.
  void updateLevels(double latDeg, double lonDeg, int finestDepth, bool wait);
  void readQueries();
  DrawState makeState(double latDeg, double lonDeg, int levelCount);
  SpiralHeightStack heightStack(const DrawState& state) const;
  void setUniforms(const gl::Program& program, const DrawState& state, const ViewSetup& view) const;
  // Draws the spiral of `state` (and, for the current state, the draped images), counting the
  // occlusion queries when `count`.
  FrameStats drawState(const DrawState& state, const ViewSetup& view, const RenderSettings& settings,
                       bool count, bool withImagery);

  std::shared_ptr<const GlobalStore> store_;
  SpiralOptions options_;
  SpiralMesh mesh_;
  gl::Buffer vertices_, strip_, fanIndices_;
  gl::VertexArray vertexArray_;
  std::uint32_t centreIndex_ = 0;
  gl::Texture baseTexture_, levelTextures_;
  gl::Texture surfaceCube_, reliefCube_, skyCube_;  // the Blue Marble set (none: the tint)
  int windowSamples_ = 0;
  SpiralHeightWindow base_;
  std::array<Level, kMaxLevels> levels_;
  std::unique_ptr<tbb::task_group> reads_ = std::make_unique<tbb::task_group>();
  gl::Program fill_, wire_;
  std::optional<GlobeSky> sky_;
  std::unique_ptr<ImageryOverlay> imagery_;
  std::optional<SpiralRadiusFeedback> feedback_;
  // Occlusion queries of the last frames (fan, last revolution), read when available.
  struct CountQueries {
    gl::Query fan, outer;
    bool issued = false;
  };
  std::array<CountQueries, 4> queries_;
  std::uint64_t frame_ = 0;
  DrawState current_, previous_;
  SpiralFrameInfo info_;
};

// "feedback" or "analytic".
std::optional<SpiralRadiusMode> parseSpiralRadiusMode(std::string_view name);
std::string_view spiralRadiusModeName(SpiralRadiusMode mode);

}  // namespace tellus
