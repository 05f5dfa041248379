// tellus view: the interactive viewer (GLFW window, Dear ImGui panel). See viewer.hpp for keys.
#include <optional>

#include <fmt/format.h>

#include "cli_numbers.hpp"
#include "cli_support.hpp"
#include "tellus/core/atomic_output.hpp"
#include "tellus/eval/camera_path.hpp"
#include "tellus/eval/renderer_registry.hpp"
#include "tellus/viewer/viewer.hpp"

namespace tellus::cli {
namespace {

struct ViewOptions {
  DemInputOptions dem;
  std::string algo;  // default: rings for a tile store, reference otherwise
  std::string size = "1280x720";
  std::string camera;
  LookOptions look;
  std::string path;
  int frames = 0;
  std::string screenshot;
  std::string record;
  bool noPanel = false;
  bool waitForTiles = false;
  RingsOptions rings;
  RagOptions rag;
};

int runView(const ViewOptions& options) {
  const bool storeInput = isTileStoreInput(options.dem.inputs);
  const std::string algo =
      options.algo.empty() ? (storeInput ? "rings" : "reference") : options.algo;
  // Everything that can be checked is checked before the (slow) load.
  if (Status s = checkRendererInput(algo, options.dem); !s) return fail(s.error());
  Result<std::pair<int, int>> size = parseImageSize(options.size);
  if (!size) return fail(size.error());
  ViewerOptions viewer;
  viewer.algo = algo;
  viewer.rings = options.rings;
  viewer.rag = options.rag;
  viewer.settings = renderSettingsOf(options.look);
  viewer.samples = options.look.samples;
  if (!options.camera.empty()) {
    Result<Camera> camera = parseCamera(options.camera);
    if (!camera) return fail(camera.error());
    viewer.camera = camera.value();
  }
  if (options.path.ends_with(".json")) {
    if (Result<CameraPath> path = loadCameraPath(options.path); !path) return fail(path.error());
  }
  viewer.path = options.path;
  viewer.frames = options.frames;
  for (const std::string& output : {options.screenshot, options.record}) {
    if (output.empty()) continue;
    if (Status writable = checkOutputWritable(output); !writable) return fail(writable.error());
  }
  viewer.screenshot = options.screenshot;
  viewer.recordFile = options.record;
  viewer.recordFromStart = !options.record.empty();
  viewer.showPanel = !options.noPanel;
  viewer.waitForTiles = options.waitForTiles;
  viewer.terrainName = fmt::format("{}", fmt::join(options.dem.inputs, ", "));

  Result<HeightGrid> grid = loadDemInputs(options.dem, rendererBytesPerSample(algo));
  if (!grid) return fail(grid.error());
  Result<std::shared_ptr<const TileStore>> store = openStoreInput(options.dem);
  if (!store) return fail(store.error());

  gl::ContextOptions contextOptions;
  contextOptions.kind = gl::ContextKind::Window;
  contextOptions.windowWidth = size.value().first;
  contextOptions.windowHeight = size.value().second;
  contextOptions.windowTitle = "Tellus";
  Result<std::unique_ptr<gl::GlContext>> context = gl::createGlContext(contextOptions);
  if (!context) return fail(context.error());
  ViewerInputs inputs;
  inputs.grid = &grid.value();
  inputs.store = store.value();
  if (Status ran = runViewer(*context.value(), inputs, viewer); !ran) return fail(ran.error());
  return 0;
}

}  // namespace

Command addViewCommand(CLI::App& app) {
  auto options = std::make_shared<ViewOptions>();
  CLI::App* sub = app.add_subcommand(
      "view",
      "Fly over a DEM or tile store in a window (WASD/QE move, drag to look, wheel speed, G walk, "
      "F frame all, M shading, X wireframe, R record path, F12 screenshot, Tab panel, Esc quit)");
  addDemInputOptions(sub, options->dem, true);
  addStoreLevelOption(sub, options->dem);
  sub->add_option("--algo", options->algo,
                  "Renderer to start with (default rings for a tile store, reference for DEM "
                  "files; the panel switches between them). " + rendererHelp());
  sub->add_option("--size", options->size, "Window size WIDTHxHEIGHT in pixels")
      ->capture_default_str();
  sub->add_option("--camera", options->camera,
                  "Start camera x,y,z,yaw,pitch,fov (as tellus render); default: an oblique view");
  addLookOptions(sub, options->look);
  sub->add_option("--path", options->path,
                  "Replay a camera path from the start: orbit, flyover, walk, rotate or a keyframe .json "
                  "(as recorded with R or --record)");
  auto* frames = sub->add_option("--frames", options->frames,
                                 "Draw this many frames and exit (a --path is sampled at that "
                                 "many frames, as tellus bench does)")
                     ->check(integerIn(1, 1000000));
  sub->add_option("--screenshot", options->screenshot, "PNG of the last frame (needs --frames)")
      ->needs(frames);
  sub->add_option("--record", options->record,
                  "Record the camera path from the start into this keyframe .json (saved on R or "
                  "at exit; replay with tellus bench --path)");
  sub->add_flag("--no-panel", options->noPanel, "Start with the panel hidden (Tab shows it)");
  sub->add_flag("--wait-tiles", options->waitForTiles,
                "Streaming renderers load every tile a frame needs before drawing it "
                "(deterministic frames for scripts)");
  sub->add_option("--patch-cells", options->rings.patchCells,
                  "Rings: mesh cells per side of a finest patch (0 = the tile size)")
      ->check(CLI::IsMember({0, 32, 64, 128, 256, 512}));
  sub->add_option("--rings", options->rings.rings, "Rings: number of rings (0 = all)")
      ->check(integerIn(0, 64));
  sub->add_option("--gpu-slots", options->rings.gpuSlots, "Rings: GPU tile cache slots")
      ->check(integerIn(4, 4096))
      ->capture_default_str();
  sub->add_option("--uploads-per-frame", options->rings.maxUploadsPerFrame,
                  "Rings: tile uploads per frame when streaming")
      ->check(integerIn(1, 1024))
      ->capture_default_str();
  addRagOptions(sub, options->rag);
  return {sub, [options] { return runView(*options); },
          [options] {
            CommandFiles files{options->dem.inputs,
                               nonEmpty({options->screenshot, options->record}), {}};
            if (options->path.ends_with(".json")) files.inputs.push_back(options->path);
            return files;
          }};
}

}  // namespace tellus::cli
