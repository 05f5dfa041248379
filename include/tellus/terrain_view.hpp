#pragma once
// Tellus's public API: drawing a terrain with any of Tellus's level-of-detail renderers, picked
// by name (the names of `tellus renderers`), into pictures, headless (EGL, no window) or into a
// context the embedder made current.
//
//   auto gl = tellus::GraphicsContext::createHeadless();
//   auto view = tellus::TerrainView::create(terrain, "rings");
//   auto picture = view.value().draw(tellus::overviewOf(terrain, 16.0 / 9.0));
#include <cstdint>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "tellus/result.hpp"
#include "tellus/terrain.hpp"

namespace tellus {

// Where the camera is and where it looks, in the terrain's world frame (terrain.hpp).
struct Viewpoint {
  double x = 0.0, y = 0.0, z = 0.0;  // metres
  double yawDeg = 0.0;               // compass heading: 0 looks north, 90 east
  double pitchDeg = -30.0;           // above the horizon: negative looks down, -90 straight down
  double fovYDeg = 45.0;             // vertical field of view, degrees
};

// A viewpoint that frames the whole terrain: heading `yawDeg`, pitched down `pitchDeg`, pulled
// back until every corner lies inside the central 90% of a picture of aspect `aspect`
// (width / height).
Viewpoint overviewOf(const Terrain& terrain, double aspect, double yawDeg = 0.0,
                     double pitchDeg = -35.0, double fovYDeg = 40.0);

// An option of a renderer, as `tellus renderers --options` lists it.
struct RendererOptionInfo {
  std::string name;          // "rings-gpu-slots": the command line's flag without its dashes
  std::string help;          // one sentence
  std::string unit;          // "px", "m", "KiB"; empty for counts, ratios and choices
  std::string defaultValue;  // as text ("80", "0.35", "off"); empty when decided at creation
};

// One renderer this API can make.
struct RendererInfo {
  std::string name;         // as `tellus renderers` lists it
  std::string description;  // one line
  std::string seed;         // the seed paper it implements ("000", "004"), "-" for references
  bool variant = false;     // a variant of another row (an ablation): benchmarks skip it
  std::vector<RendererOptionInfo> options;
};

// The renderers that draw a flat terrain from a store or its finest grid, in Tellus's order.
// (The globe and stack-terrain renderers draw other inputs: `tellus render` has them.)
std::vector<RendererInfo> listRenderers();

// A renderer's options by name, values as text: {"rings-gpu-slots", "64"}. Values are checked
// as the command line checks them (range, choices); an unknown name is an error.
using RendererOptions = std::map<std::string, std::string>;

// What one frame drew and streamed.
struct FrameReport {
  std::uint64_t triangles = 0;
  std::uint64_t vertices = 0;
  std::uint64_t drawCalls = 0;
  std::uint64_t tilesWanted = 0;    // tiles the frame needs (streaming renderers)
  std::uint64_t tilesResident = 0;  // tiles in the GPU cache after the frame
  std::uint64_t tilesLoaded = 0;    // tiles that became resident for this frame
  std::vector<std::string> lines;   // the renderer's own account of the frame, one line each
};

// 8-bit RGB, rows top first.
struct Picture {
  int width = 0, height = 0;
  std::vector<std::uint8_t> rgb;  // width * height * 3 bytes
  // Writes a PNG (through a temporary file: never a half-written one).
  Status savePng(const std::string& path) const;
};

// An OpenGL 4.5 core context. Everything that draws needs one current on its thread; the
// context must outlive the views made while it was current.
class GraphicsContext {
 public:
  // A headless context through EGL (a GPU, or Mesa's software rasteriser), made current on
  // the calling thread.
  static Result<GraphicsContext> createHeadless();

  GraphicsContext(GraphicsContext&&) noexcept;
  GraphicsContext& operator=(GraphicsContext&&) noexcept;
  ~GraphicsContext();

  struct State;

 private:
  explicit GraphicsContext(std::unique_ptr<State> state);
  std::unique_ptr<State> state_;
};

// How a view draws.
struct ViewSettings {
  int width = 1280, height = 720;  // pixels of the pictures drawn
  int samples = 4;                 // multisampling per pixel (1: none)
  // Stills and tests: every frame waits for the tiles it needs. Interactive use: false, tiles
  // stream in over the following frames and the frame draws coarser ones meanwhile.
  bool waitForTiles = true;
  RendererOptions options;  // the renderer's own options (listRenderers())
};

// One renderer drawing one terrain. Needs a current GL context (GraphicsContext) on the thread
// that creates it and draws with it.
class TerrainView {
 public:
  // Errors: an unknown renderer (the message lists the names), an option it does not have or
  // a value out of range, a terrain too large for the memory left (renderers that copy the
  // whole finest grid), a failure to read the store.
  static Result<TerrainView> create(const Terrain& terrain, const std::string& renderer,
                                    const ViewSettings& settings = {});

  // Draws one frame seen from `viewpoint`: its picture, and what it drew in `report`.
  Result<Picture> draw(const Viewpoint& viewpoint, FrameReport* report = nullptr);

  const std::string& renderer() const;

  TerrainView(TerrainView&&) noexcept;
  TerrainView& operator=(TerrainView&&) noexcept;
  ~TerrainView();

  struct State;

 private:
  explicit TerrainView(std::unique_ptr<State> state);
  std::unique_ptr<State> state_;
};

}  // namespace tellus
