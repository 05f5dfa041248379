#pragma once
// `tellus view`: an interactive window onto a terrain, with any renderer of the registry, a fly
// camera (fly_camera.hpp), a Dear ImGui panel (viewer_panel.hpp), screenshots and path
// recording (path_recorder.hpp). Scripts and tests run it for a fixed number of frames, along
// a camera path, and take a screenshot at the end.
//
// On the globe (a globe renderer, a lat/lon grid) the camera orbits high up and flies near the
// ground (globe_camera.hpp): drag turns the globe, the wheel zooms towards the cursor, F shows
// the whole globe, G drops to walking height.
//
// Keys (when the panel does not have the keyboard):
//   W A S D  move forward, left, back, right      Q E   down, up       Shift  4x faster
//   mouse drag (either button) look around         wheel  speed -/+ 25%
//   G  drop to walking height                       F     frame the whole terrain
//   M  next shading mode (lit, LOD, SSE)            X     wireframe on/off
//   R  start/stop recording the path                F12   screenshot
//   Tab  hide/show the panel                        Esc   quit
//   Ctrl + left / right click  the stacks brush (--algo stacks): add material / carve
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "tellus/core/camera.hpp"
#include "tellus/core/geo_camera.hpp"
#include "tellus/dem/drape_image.hpp"
#include "tellus/dem/geoid.hpp"
#include "tellus/eval/geo_camera_path.hpp"
#include "tellus/render/imagery/imagery_textures.hpp"
#include "tellus/tiles/global_store.hpp"
#include "tellus/core/result.hpp"
#include "tellus/dem/height_grid.hpp"
#include "tellus/gl/gl_context.hpp"
#include "tellus/render/registry/renderer_registry.hpp"
#include "tellus/formats/stacks/material_stack.hpp"
#include "tellus/formats/stacks/stack_edit.hpp"
#include "tellus/render/terrain_renderer.hpp"
#include "tellus/tiles/tile_store.hpp"

namespace tellus {

struct ViewerOptions {
  std::string algo = "reference";  // initial renderer (a name of the registry)
  RendererSettings renderers;      // initial options of every renderer family (the panel edits them)
  std::filesystem::path inputPath;  // the input, for renderers' files beside it
  RenderSettings settings;         // initial shading (haze is fitted to each view)
  int samples = 4;                 // MSAA samples per pixel
  std::optional<Camera> camera;    // initial camera; default: the "oblique" named view
  // A path to replay (built-in name or keyframe JSON), from the first frame. With `frames`
  // the path is sampled at that many frames as `tellus bench` does, else it plays in real
  // time and hands the camera back to the user at its end.
  std::string path;
  int frames = 0;                    // > 0: draw this many frames and exit
  std::filesystem::path screenshot;  // written after the last frame (with `frames`)
  // Where the recorded path goes; recording starts at the first frame when `recordFromStart`
  // (and is saved at exit), else on R. Empty: tellus-path-NNN.json in the working directory.
  std::filesystem::path recordFile;
  bool recordFromStart = false;
  bool showPanel = true;
  bool waitForTiles = false;  // streaming renderers load every tile before drawing a frame
  // On a global store the globe reference draws the store's cut (its finest tiles wherever they
  // show); false: the viewer's grid, one region at one depth (--store-depth, --region).
  bool globeReferenceReadsStore = true;
  std::string terrainName;    // shown in the panel and the window title
  // Globe renderers: the start camera (default: the whole globe from 20,000 km above the grid's
  // centre) and what globe paths (descent, walk, lowflight) are about.
  std::optional<GeoCamera> geoCamera;
  GeoPathTarget geoTarget;
  // Material stacks: the file they came from (the panel's save button writes the edits back
  // to it, atomically), strokes to apply by script and whether to save them at exit.
  std::filesystem::path stackFile;
  std::vector<ScriptedStackEdit> stackEdits;
  bool saveStackEdits = false;
  // Imagery draped over the terrain (render/imagery/imagery_textures.hpp), later ones on
  // top, their pyramids cached in `imageryCache`; the panel turns it on and off.
  std::vector<std::filesystem::path> imagery;
  std::filesystem::path imageryCache;
  ImageryBudget imageryBudget;
};

struct ViewerInputs {
  const HeightGrid* grid = nullptr;        // full-resolution heights (required)
  std::shared_ptr<const TileStore> store;  // for the streaming renderers, when there is one
  const Geoid* geoid = nullptr;            // globe renderers (may be null)
  const DrapeImage* drape = nullptr;       // globe renderers: a colour map (may be null)
  std::shared_ptr<const GlobalStore> globalStore;  // for the renderers that stream from it, when the input is a global store
  // Material stacks (a .tstack): the stack renderers draw them; `grid` is then their top surface.
  const std::vector<StackTerrain>* stacks = nullptr;  // every level, finest first
};

// Runs the viewer in `context`'s window until the user closes it (or `frames` are drawn).
// Errors: no window, a renderer that cannot be made, a path that cannot be read, a screenshot
// or path that cannot be written.
Status runViewer(gl::GlContext& context, const ViewerInputs& inputs, const ViewerOptions& options);

}  // namespace tellus
