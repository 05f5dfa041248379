// tellus view: the interactive viewer (GLFW window, Dear ImGui panel). See viewer.hpp for keys.
#include <algorithm>
#include <array>
#include <charconv>
#include <optional>

#include <fmt/format.h>

#include "cli_numbers.hpp"
#include "cli_support.hpp"
#include "stack_cli.hpp"
#include "tellus/formats/stacks/stack_surface.hpp"
#include "global_store_cli.hpp"
#include "tellus/dem/drape_image.hpp"
#include "tellus/dem/geoid.hpp"
#include "tellus/core/atomic_output.hpp"
#include "tellus/core/number_fields.hpp"
#include "tellus/eval/camera_path.hpp"
#include "renderer_cli_options.hpp"
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
  RendererSettings renderers;  // every --<family>-* option
  std::vector<std::string> stackEdits;  // FRAME:x,y,z,r:MATERIAL|remove
  bool saveStackEdits = false;
  // Globe renderers.
  std::string geoCamera, geoid, drape, target, region;
  int storeDepth = -1;
  ImageryCliOptions imagery;  // --imagery: draped over the terrain
};

// One --stack-edit: FRAME:x,y,z,r:MATERIAL, MATERIAL rock, soil, grass, an id or remove.
Result<ScriptedStackEdit> parseScriptedStackEdit(const std::string& text) {
  const std::size_t first = text.find(':'), last = text.rfind(':');
  if (first == std::string::npos || first == last) {
    return makeError("--stack-edit '{}': give FRAME:x,y,z,r:MATERIAL (or :remove)", text);
  }
  ScriptedStackEdit scripted;
  const std::string frame = text.substr(0, first);
  const auto [end, ec] = std::from_chars(frame.data(), frame.data() + frame.size(), scripted.frame);
  if (frame.empty() || ec != std::errc() || end != frame.data() + frame.size() || scripted.frame < 0) {
    return makeError("--stack-edit '{}': the frame '{}' is not a frame number", text, frame);
  }
  static constexpr std::array<const char*, 4> kFields = {"x", "y", "z", "r"};
  Result<std::vector<double>> sphere =
      parseNumberFields(text.substr(first + 1, last - first - 1), kFields, "--stack-edit sphere");
  if (!sphere) return sphere.error();
  scripted.edit = {(*sphere)[0], (*sphere)[1], (*sphere)[2], (*sphere)[3], kAir};
  const std::string material = text.substr(last + 1);
  if (material != "remove") {
    Result<StackMaterial> parsed = parseStackMaterial(material);
    if (!parsed) return makeError("--stack-edit '{}': {}", text, parsed.error().message);
    scripted.edit.material = parsed.value();
  }
  return scripted;
}

// The globe session's grid: a global store's region (--store-depth / --region, else what the
// start camera sees, else the whole globe) at the deepest depth that fits, or a lat/lon DEM.
// On a store it is the ground under the camera (and what globe-reference draws when a depth or
// region is given; without, it draws the store's cut).
Result<HeightGrid> loadGlobeGrid(const ViewOptions& options, const std::optional<GeoCamera>& camera,
                                 double aspect) {
  if (!(options.dem.classified().kind == TerrainInputKind::GlobalStore)) {
    if (options.storeDepth >= 0 || !options.region.empty()) {
      return makeError("--store-depth and --region apply to global stores");
    }
    Result<HeightGrid> grid = loadDemInputs(options.dem, rendererBytesPerSample(options.algo));
    if (grid && !grid->georef.isGeographic) {
      return makeError("globe renderers need a global store or a DEM in latitude/longitude");
    }
    return grid;
  }
  Result<std::shared_ptr<GlobalStore>> store = openGlobalStoreInput(options.dem);
  if (!store) return store.error();
  Result<GlobalRegionRequest> request = regionRequest(
      options.storeDepth, options.region, camera, aspect, std::uint64_t(16) << 20);  // every frame
  if (!request) return request.error();
  return loadGlobalStoreRegion(*store.value(), request.value());
}

int runView(const ViewOptions& options) {
  const bool storeInput = options.dem.classified().isStore();
  const bool stackInput = options.dem.inputs.size() == 1 && isStackFile(options.dem.inputs[0]);
  const std::string algo = !options.algo.empty() ? options.algo
                           : stackInput          ? "stacks"
                           : storeInput          ? "rings"
                                                 : "reference";
  // Everything that can be checked is checked before the (slow) load.
  if (Status s = checkRendererInput(algo, options.dem, options.renderers); !s) return fail(s.error());
  const bool globe = rendererDrawsGlobe(algo);
  if (!globe && (!options.geoCamera.empty() || !options.geoid.empty() || !options.drape.empty() ||
                 !options.target.empty() || options.storeDepth >= 0 || !options.region.empty())) {
    return fail(makeError("--geo-camera, --geoid, --drape, --target, --store-depth and --region "
                          "are for globe renderers (--algo globe-reference)"));
  }
  if (globe && !options.camera.empty()) {
    return fail(makeError("on the globe give --geo-camera (not --camera)"));
  }
  Result<std::pair<int, int>> size = parseImageSize(options.size);
  if (!size) return fail(size.error());
  ViewerOptions viewer;
  viewer.algo = algo;
  viewer.renderers = options.renderers;
  viewer.inputPath = localInputPath(options.dem);
  if ((!options.stackEdits.empty() || options.saveStackEdits) && !stackInput) {
    return fail(makeError("--stack-edit and --save-stack-edits edit a .tstack"));
  }
  if (stackInput) viewer.stackFile = options.dem.inputs[0];
  for (const std::string& text : options.stackEdits) {
    Result<ScriptedStackEdit> scripted = parseScriptedStackEdit(text);
    if (!scripted) return fail(scripted.error());
    viewer.stackEdits.push_back(scripted.value());
  }
  std::stable_sort(viewer.stackEdits.begin(), viewer.stackEdits.end(),
                   [](const ScriptedStackEdit& a, const ScriptedStackEdit& b) { return a.frame < b.frame; });
  viewer.saveStackEdits = options.saveStackEdits;
  if (options.imagery.any()) {
    viewer.imagery.assign(options.imagery.files.begin(), options.imagery.files.end());
    viewer.imageryCache = imageryCacheFolder(options.dem.inputs.front());
    viewer.imageryBudget.memoryBytes = std::uint64_t(options.imagery.budgetMiB * 1024.0 * 1024.0);
    viewer.imageryBudget.uploadsPerFrame = options.imagery.uploadsPerFrame;
  }
  viewer.settings = renderSettingsOf(options.look);
  viewer.samples = options.look.samples;
  if (!options.camera.empty()) {
    Result<Camera> camera = parseCamera(options.camera);
    if (!camera) return fail(camera.error());
    viewer.camera = camera.value();
  }
  if (options.path.ends_with(".json") && !globe) {
    if (Result<CameraPath> path = loadCameraPath(options.path); !path) return fail(path.error());
  }
  std::optional<Geoid> geoid;
  std::optional<DrapeImage> drape;
  if (globe) {
    if (!options.geoCamera.empty()) {
      Result<GeoCamera> camera = parseGeoCamera(options.geoCamera);
      if (!camera) return fail(camera.error());
      viewer.geoCamera = camera.value();
    }
    if (!options.geoid.empty()) {
      Result<Geoid> loaded = Geoid::load(options.geoid);
      if (!loaded) return fail(loaded.error());
      geoid = std::move(loaded.value());
    }
    if (!options.drape.empty()) {
      Result<DrapeImage> loaded = loadDrapeImage(options.drape);
      if (!loaded) return fail(loaded.error());
      drape = std::move(loaded.value());
    }
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
  viewer.globeReferenceReadsStore = options.storeDepth < 0 && options.region.empty();
  viewer.terrainName = fmt::format("{}", fmt::join(options.dem.inputs, ", "));

  ViewOptions resolved = options;
  resolved.algo = algo;
  // Material stacks: the finest level, and its top surface as the viewer's ground.
  std::optional<std::vector<StackTerrain>> stacks;
  std::optional<HeightGrid> stackSurface;  // georeferenced: imagery is placed by it
  if (stackInput) {
    Result<LoadedStacks> loaded = loadStacks(options.dem.inputs[0], options.imagery.any());
    if (!loaded) return fail(loaded.error());
    stacks = std::move(loaded->levels);
    stackSurface = std::move(loaded->surface);
  }
  Result<HeightGrid> grid =
      stacks  ? Result<HeightGrid>(std::move(*stackSurface))
      : globe ? loadGlobeGrid(resolved, viewer.geoCamera,
                              double(size->first) / double(size->second))
              : loadDemInputs(options.dem, rendererBytesPerSample(algo));
  if (!grid) return fail(grid.error());
  if (globe) {
    if (!options.target.empty()) {
      Result<GeoCamera> target = parseGeoCamera(options.target + ",0,0,0,45");
      if (!target) return fail(makeError("--target '{}' is not LAT,LON in degrees", options.target));
      viewer.geoTarget = {target->latDeg, target->lonDeg};
    } else {
      // The highest sample in view, as tellus bench does for a DEM.
      int bx = 0, by = 0;
      for (int y = 0; y < grid->height; ++y) {
        for (int x = 0; x < grid->width; ++x) {
          if (grid->at(x, y) > grid->at(bx, by)) bx = x, by = y;
        }
      }
      const auto& gt = grid->georef.geoTransform;
      viewer.geoTarget = {gt[3] + (by + 0.5) * gt[5], gt[0] + (bx + 0.5) * gt[1]};
    }
  }
  Result<std::shared_ptr<const TileStore>> store =
      globe ? std::shared_ptr<const TileStore>() : openStoreInput(options.dem);
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
  if (globe && options.dem.classified().kind == TerrainInputKind::GlobalStore) {
    // The renderers that stream from the global store read it themselves; the grid
    // above is the ground under the camera.
    Result<std::shared_ptr<GlobalStore>> opened = openGlobalStoreInput(options.dem);
    if (!opened) return fail(opened.error());
    inputs.globalStore = opened.value();
  }
  inputs.geoid = geoid ? &*geoid : nullptr;
  inputs.drape = drape ? &*drape : nullptr;
  inputs.stacks = stacks ? &*stacks : nullptr;
  if (Status ran = runViewer(*context.value(), inputs, viewer); !ran) return fail(ran.error());
  return 0;
}

}  // namespace

Command addViewCommand(CLI::App& app) {
  auto options = std::make_shared<ViewOptions>();
  CLI::App* sub = app.add_subcommand(
      "view",
      "Fly over a DEM or tile store in a window (WASD/QE move, drag to look, wheel speed, G walk, "
      "F frame all, M shading, X wireframe, R record path, F12 screenshot, Tab panel, Esc quit); "
      "on the globe (--algo globe-reference) drag turns the globe and the wheel zooms to the "
      "cursor");
  addDemInputOptions(sub, options->dem, true, InputKinds::AnyTerrain);
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
  addRendererOptions(sub, options->renderers);
  addImageryOptions(sub, options->imagery);
  sub->add_option("--stack-edit", options->stackEdits,
                  "Stacks (--algo stacks): a brush stroke before frame FRAME, "
                  "FRAME:x,y,z,r:MATERIAL with the sphere in metres (x east, y north of the "
                  "south-west stack, z above the base) and MATERIAL rock, soil, grass, an id or "
                  "remove; repeatable (the mouse: Ctrl + left/right click)");
  sub->add_flag("--save-stack-edits", options->saveStackEdits,
                "Stacks: write the edits back to the .tstack at exit (atomically)");
  sub->add_option("--geo-camera", options->geoCamera,
                  "Globe renderers: start camera lat,lon,altitude,heading,pitch,fov (default: the "
                  "whole globe from 20,000 km)");
  sub->add_option("--geoid", options->geoid, "Globe renderers: a geoid grid (egm96_15.gtx)");
  sub->add_option("--drape", options->drape,
                  "Globe renderers: a lat/lon colour map to drape (BlueMarbleAlbedo.jpg)");
  sub->add_option("--target", options->target,
                  "Globe paths (--path descent, walk, lowflight): LAT,LON (default: the highest "
                  "sample drawn)");
  sub->add_option("--store-depth", options->storeDepth,
                  "Global stores: globe-reference draws one region at this depth (default: the "
                  "store's finest tiles wherever they show)")
      ->check(integerIn(0, GlobalTiling::kMaxDepth));
  sub->add_option("--region", options->region,
                  "Global stores: globe-reference draws this region (WEST,SOUTH,EAST,NORTH "
                  "degrees) at one depth (default: the store's finest tiles wherever they show)");
  return {sub, [options] { return runView(*options); },
          [options] {
            CommandFiles files{options->dem.inputs,
                               nonEmpty({options->screenshot, options->record}), {}};
            files.inputs.insert(files.inputs.end(), options->imagery.files.begin(), options->imagery.files.end());
            if (options->dem.inputs.size() == 1 && isStackFile(options->dem.inputs[0])) {
              // A .tstack is read, then may be replaced atomically with the brush's edits (the
              // panel's save button, --save-stack-edits): not an input to protect.
              files.outputs.insert(files.outputs.end(), files.inputs.begin(), files.inputs.end());
              files.inputs.clear();
            }
            if (options->path.ends_with(".json")) files.inputs.push_back(options->path);
            addRendererReadFiles(files, localInputPath(options->dem), options->geoid, options->drape,
                                 options->renderers);
            return files;
          }};
}

}  // namespace tellus::cli
