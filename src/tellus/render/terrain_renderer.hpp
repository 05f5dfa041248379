#pragma once
// The interface every terrain renderer implements, so that `--algo NAME` can pick one and the
// evaluation harness can run them all on the same camera path.
//
// Per frame the harness calls prepare(view, settings) (the CPU work that depends on the view: LOD
// selection, culling, streaming requests; timed as "CPU LOD ms") and then draw(view, settings)
// into the bound target (timed with GL timer queries as "GPU ms"). Needs a current GL context.
#include <cstdint>
#include <limits>
#include <optional>
#include <map>
#include <string>
#include <string_view>
#include <vector>

#include "tellus/core/camera.hpp"
#include "tellus/core/result.hpp"
#include "tellus/render/shading/terrain_shading.hpp"

namespace tellus {

class ImageryTextures;

// How the terrain is coloured: lit hypsometric tints; the same light with each patch tinted
// by its level of detail (renderers without LOD draw everything as level 0); or by the
// screen-space error the drawn data may have: the geometric error of the pyramid level it comes
// from (TileStats::geometricErrorM, 0 for the full-resolution grid) projected at the pixel's
// distance, green at 0 px through yellow to red at RenderSettings::sseRedPx and beyond.
enum class ShadingMode { Lit, LevelOfDetail, ScreenSpaceError };

// "lit", "lod" or "sse" (the names of --shading); error otherwise.
Result<ShadingMode> parseShadingMode(std::string_view name);
std::string_view shadingModeName(ShadingMode mode);

struct RenderSettings {
  ShadingParams shading;
  ShadingMode mode = ShadingMode::Lit;
  bool wireframe = false;  // overlay the triangle edges
  float verticalExaggeration = 1.0f;
  float sseRedPx = 4.0f;  // ScreenSpaceError: the error drawn fully red, pixels
  // Globe renderers: draw the atmosphere behind the terrain (stills and the viewer; the bench
  // leaves it off so that the crack test sees its sentinel background).
  bool sky = false;
  // Imagery draped over the flat renderers' tint (render/imagery/imagery_textures.hpp), bound
  // to every terrain program by applyShadingMode; null: the tint alone. Not owned: the frame
  // loop that owns it calls its beginFrame() and endFrame().
  ImageryTextures* imagery = nullptr;
};

// What one frame submitted. Renderers fill the geometry counts and their streaming counters;
// the harness adds the timings.
struct FrameStats {
  std::uint64_t triangles = 0;
  std::uint64_t vertices = 0;
  std::uint64_t drawCalls = 0;
  std::uint64_t tilesLoaded = 0;    // tiles that became resident for this frame
  std::uint64_t cacheMisses = 0;    // tiles wanted but not resident
  std::uint64_t tilesWanted = 0;    // tiles the frame needs (hits = wanted - misses)
  std::uint64_t tilesResident = 0;  // tiles in the GPU cache after the frame
  std::uint64_t uploadBytes = 0;    // data sent to the GPU for the frame (or to its copiers)
  // CPU time the renderer's background threads (tile loads, reorganising data) spent
  // since the previous frame's draw(), summed over the threads: the render thread's is timed
  // by the harness (CPU LOD, submit).
  double backgroundCpuMs = 0.0;
  // Render-thread ms the renderer spent updating its streamed textures for the frame (reading
  // feedback, choosing, transferring: imagery quadtrees); -1: it has none.
  double textureUpdateMs = -1.0;
  // The renderer's own stages, render-thread milliseconds by name ("lod_priority",
  // "mesh_build"): what its algorithm spends time on, as it reports them (core/stopwatch.hpp).
  // The bench reports each as <name>_ms; empty: none reported.
  std::map<std::string, double> stageMs;
  // The frame was drawn with less geometry than its LOD selection made, because a buffer
  // was too small (any renderer that captures geometry into buffers that grow: RAG's
  // transform feedback). The bench counts such frames.
  bool truncated = false;
  // Calls of the frame (prepare, draw) that made the render thread wait for the GPU:
  // read-backs, glFinish, query results not ready, fence waits (gl/gpu_wait.hpp). Counted by
  // the harness, not the renderer; the benchmark's own waits (finishStats, --finish, the
  // read-backs of --quality) are not in it.
  std::uint64_t gpuWaits = 0;
};

// Sets the uniforms of shading.glsl and lod_colours.glsl on a terrain fill program: the
// shading parameters, the mode and the screen-space error scale of `view`, and binds the
// imagery (imagery.glsl) when the settings have it.
void applyShadingMode(const gl::Program& program, const ViewSetup& view,
                      const RenderSettings& settings);

class TerrainRenderer {
 public:
  virtual ~TerrainRenderer() = default;
  virtual std::string_view name() const = 0;
  // CPU work for this view (LOD selection, culling, streaming requests). Default: nothing.
  virtual void prepare(const ViewSetup& view, const RenderSettings& settings) {
    (void)view;
    (void)settings;
  }
  // Draws into the bound framebuffer, whose depth state OffscreenTarget::begin() set.
  virtual FrameStats draw(const ViewSetup& view, const RenderSettings& settings) = 0;
  // The first error reading the renderer's data (a patch or tile that fails its checksum or
  // holds impossible values), kept once it happened: the frame drew without that piece, and a
  // still, a benchmark or the viewer's exit status must not pass it off as good. Default: none.
  virtual std::optional<Error> dataError() const { return std::nullopt; }
  // Completes the last draw()'s counts that only the GPU knows (RAG's triangles, from queries
  // its draw() does not wait for), waiting for them if needed. The benchmark calls it after a
  // frame's timing, never inside it. Default: the counts are complete already.
  virtual void finishStats(FrameStats& stats) { (void)stats; }
  // For the popping metric (bench --quality): draws, from `view`, the geometry of the frame
  // before the last draw() (that frame's level-of-detail selection and the data it read), into
  // the bound framebuffer, without changing what the next frame draws. Returns false and draws
  // nothing when there is no earlier frame or the geometry never depends on the view (the
  // reference: its popping is 0). Call after draw() and finishStats().
  virtual bool drawPreviousSelection(const ViewSetup& view, const RenderSettings& settings) {
    (void)view;
    (void)settings;
    return false;
  }
  // For the crack metric of renderers whose meshes bound a closed solid (stack terrain): draws
  // the last draw()'s geometry from `view` with its front faces culled, into the bound
  // framebuffer, without changing what the next frame draws. A pixel it covers has a view ray
  // that leaves the solid somewhere; a background pixel of the frame it does not cover was
  // reached through open air only. Returns false and draws nothing when the meshes are not
  // closed (height fields) or nothing was drawn yet.
  virtual bool drawLastFrameBackFaces(const ViewSetup& view, const RenderSettings& settings) {
    (void)view;
    (void)settings;
    return false;
  }
  // What the last frame did beyond FrameStats, a line each, for a person (the viewer's panel
  // prints them without knowing the algorithm): patches and fallbacks, passes, queue work,
  // caches. Default: nothing more to say.
  virtual std::vector<std::string> frameReport() const { return {}; }
  // Globe renderers that stream their own data: the ellipsoidal height, in
  // metres, of the ground they draw under (latDeg, lonDeg), for a camera that must stay above
  // it; NaN where they do not know. Default: NaN.
  virtual double drawnGroundM(double latDeg, double lonDeg) const {
    (void)latDeg;
    (void)lonDeg;
    return std::numeric_limits<double>::quiet_NaN();
  }
};

// "1234", "12.3 k", "12.3 M": a count for frameReport() lines.
std::string countText(std::uint64_t n);

}  // namespace tellus
