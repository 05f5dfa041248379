// tellus render: one PNG of a terrain from a camera or a named view.
#include <algorithm>
#include <cmath>
#include <optional>

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include "cli_numbers.hpp"
#include "cli_support.hpp"
#include "globe_still.hpp"
#include "stack_cli.hpp"
#include "tellus/formats/stacks/stack_surface.hpp"
#include "tellus/core/atomic_output.hpp"
#include "renderer_cli_options.hpp"
#include "global_store_cli.hpp"
#include "tellus/core/geo_camera.hpp"
#include "tellus/core/geodesy.hpp"
#include "tellus/dem/drape_image.hpp"
#include "tellus/dem/geoid.hpp"
#include "tellus/render/output/named_views.hpp"
#include "tellus/render/output/snapshot.hpp"

namespace tellus::cli {
namespace {

struct RenderOptions {
  DemInputOptions dem;
  std::string output;
  std::string size = "1280x720";
  std::string camera;
  std::string view;
  std::string geoCamera;
  std::string geoid;
  LookOptions look;
  std::string context = "headless";
  std::string algo;  // empty: reference, or stacks-full for a .tstack
  RendererSettings renderers;  // every --<family>-* option
  int storeDepth = -1;  // global stores: -1 chooses from the camera
  std::string region;
  std::string drape;  // globe renderers: a lat/lon colour map (Blue Marble)
  // A flight (command_render_path.cpp): the camera path, its frames (0: 30 a second of the
  // path's time), the video, and the globe paths' target.
  std::string path;
  int frames = 0;
  VideoCliOptions video;
  std::string target;
  ImageryCliOptions imagery;  // --imagery: draped over the terrain
};

// A globe view from a DEM in latitude/longitude: the explicit --geo-camera, or straight down
// on the grid's centre from high enough to see all of it (at most 20,000 km: the whole disc).
GeoCamera defaultGeoCamera(const HeightGrid& grid) {
  const auto& gt = grid.georef.geoTransform;
  GeoCamera camera;
  camera.latDeg = gt[3] + 0.5 * grid.height * gt[5];
  camera.lonDeg = gt[0] + 0.5 * grid.width * gt[1];
  const double latRad = camera.latDeg * wgs84::kDegree;
  const double extentM =
      std::max(wgs84::northSouthMetres(latRad, std::abs(grid.height * gt[5]) * wgs84::kDegree),
               wgs84::eastWestMetres(latRad, std::abs(grid.width * gt[1]) * wgs84::kDegree));
  camera.altitudeM = std::clamp(1.2 * extentM, 2000.0, 20'000'000.0);
  camera.pitchDeg = -90.0;
  camera.fovYDeg = 45.0;
  return camera;
}

int runRender(RenderOptions options) {
  const bool stackInput = options.dem.inputs.size() == 1 && isStackFile(options.dem.inputs[0]);
  if (options.algo.empty()) options.algo = stackInput ? "stacks-full" : "reference";
  if (!options.path.empty()) {
    if (!options.output.empty() || !options.camera.empty() || !options.view.empty() || !options.geoCamera.empty()) {
      return fail(makeError("render --path flies the path into --video: -o, --camera, --view and --geo-camera are for stills"));
    }
    BenchPathOptions flight;
    flight.dem = options.dem;
    flight.algos = options.algo;
    flight.path = options.path;
    flight.frames = options.frames;
    flight.size = options.size;
    flight.renderers = options.renderers;
    flight.target = options.target;
    flight.geoid = options.geoid;
    flight.video = options.video;
    flight.imagery = options.imagery;
    return runRenderAlongPath(flight, options.look);
  }
  if (!options.video.file.empty()) return fail(makeError("--video needs --path (a still is a PNG: -o FILE)"));
  if (options.output.empty()) return fail(makeError("render: give -o FILE.png (or --path P --video FILE for a flight)"));
  const bool globe = rendererDrawsGlobe(options.algo);
  if (Status s = checkRendererInput(options.algo, options.dem, options.renderers); !s) return fail(s.error());
  if (globe && (!options.camera.empty() || !options.view.empty())) {
    return fail(makeError("renderer '{}' draws on the globe: give --geo-camera "
                          "lat,lon,altitude,heading,pitch,fov instead of --camera or --view",
                          options.algo));
  }
  if (!globe && (!options.geoCamera.empty() || !options.geoid.empty() || !options.drape.empty())) {
    return fail(makeError("--geo-camera, --geoid and --drape are for globe renderers (--algo "
                          "globe-reference); '{}' draws on the flat world",
                          options.algo));
  }
  Result<std::pair<int, int>> size = parseImageSize(options.size);
  if (!size) return fail(size.error());
  std::optional<Camera> explicitCamera;  // --camera, parsed before the (slow) load
  if (!options.camera.empty()) {
    Result<Camera> parsed = parseCamera(options.camera);
    if (!parsed) return fail(parsed.error());
    explicitCamera = parsed.value();
  }
  std::optional<GeoCamera> geoCamera;
  if (!options.geoCamera.empty()) {
    Result<GeoCamera> parsed = parseGeoCamera(options.geoCamera);
    if (!parsed) return fail(parsed.error());
    geoCamera = parsed.value();
  }
  std::optional<Geoid> geoid;
  if (!options.geoid.empty()) {
    Result<Geoid> loaded = Geoid::load(options.geoid);
    if (!loaded) return fail(loaded.error());
    geoid = std::move(loaded.value());
  } else if (globe) {
    spdlog::info("no --geoid: heights are drawn as ellipsoidal (off by the geoid undulation, up "
                 "to 107 m; EGM96: --geoid egm96_15.gtx)");
  }
  std::optional<DrapeImage> drape;
  if (!options.drape.empty()) {
    Result<DrapeImage> loaded = loadDrapeImage(options.drape);
    if (!loaded) return fail(loaded.error());
    drape = std::move(loaded.value());
  }
  if (Status writable = checkOutputWritable(options.output); !writable)
    return fail(writable.error());

  const bool globalStore = options.dem.classified().kind == TerrainInputKind::GlobalStore;
  if (globalStore && !globe) {
    return fail(makeError("'{}' is a global store: draw it with a globe renderer (--algo "
                          "globe-reference)",
                          options.dem.inputs[0]));
  }
  if (!globalStore && (options.storeDepth >= 0 || !options.region.empty())) {
    return fail(makeError("--store-depth and --region apply to global stores (tellus build "
                          "--global)"));
  }
  // Renderers that stream from the global store choose their blocks themselves.
  const bool streams = rendererNeedsGlobalStore(options.algo);
  if (streams && (options.storeDepth >= 0 || !options.region.empty())) {
    return fail(makeError("--store-depth and --region choose what globe-reference draws; '{}' "
                          "chooses its blocks from the camera",
                          options.algo));
  }
  if (streams && !geoCamera) {
    return fail(makeError("renderer '{}' needs a camera: give --geo-camera "
                          "lat,lon,alt,heading,pitch,fov",
                          options.algo));
  }
  // The globe reference on a store, with a camera and no region asked for: its cut of the
  // store's finest tiles (globe_store_cut.hpp) instead of one region at one depth.
  const bool storeCut = globalStore && options.algo == "globe-reference" && geoCamera &&
                        options.storeDepth < 0 && options.region.empty();
  const bool readsStore = streams || storeCut;
  // Stack terrain: the finest level, and its top surface for the named views.
  std::optional<std::vector<StackTerrain>> stacks;
  std::optional<HeightGrid> stackSurface;  // georeferenced: imagery is placed by it
  if (stackInput) {
    Result<LoadedStacks> loaded = loadStacks(options.dem.inputs[0], options.imagery.any());
    if (!loaded) return fail(loaded.error());
    stacks = std::move(loaded->levels);
    stackSurface = std::move(loaded->surface);
  }
  // A global store, opened once from the container its classification read: the view's region
  // for globe-reference, the whole store for the renderers that stream from it.
  std::shared_ptr<GlobalStore> global;
  if (globalStore) {
    Result<std::shared_ptr<GlobalStore>> opened = openGlobalStoreInput(options.dem);
    if (!opened) return fail(opened.error());
    global = opened.value();
  }
  Result<HeightGrid> grid = stacks        ? Result<HeightGrid>(std::move(*stackSurface))
                            : readsStore  ? Result<HeightGrid>(HeightGrid{})
                            : globalStore ? loadGlobalStoreView(*global, options.dem.inputs[0],
                                                              options.storeDepth, options.region,
                                                              geoCamera,
                                                              double(size->first) / size->second)
                                        : loadDemInputs(options.dem,
                                                        rendererBytesPerSample(options.algo));
  if (!grid) return fail(grid.error());
  const auto [width, height] = size.value();
  Camera camera;
  if (globe) {
    if (!geoCamera) geoCamera = defaultGeoCamera(grid.value());
  } else if (explicitCamera) {
    camera = *explicitCamera;
  } else {
    Result<Camera> named = namedView(options.view.empty() ? "overview" : options.view, grid.value(),
                                     double(width) / double(height));
    if (!named) return fail(named.error());
    camera = named.value();
  }

  Result<std::unique_ptr<gl::GlContext>> context = createContext(options.context);
  if (!context) return fail(context.error());
  Result<std::shared_ptr<const TileStore>> store =
      globalStore ? std::shared_ptr<const TileStore>() : openStoreInput(options.dem);
  if (!store) return fail(store.error());
  RendererInputs inputs;
  inputs.grid = readsStore ? nullptr : &grid.value();
  inputs.store = store.value();
  if (readsStore) inputs.globalStore = global;
  inputs.waitForTiles = true;  // a still waits for every tile it shows
  inputs.inputPath = localInputPath(options.dem);
  inputs.geoid = geoid ? &*geoid : nullptr;
  inputs.drape = drape ? &*drape : nullptr;
  inputs.stacks = stacks ? &*stacks : nullptr;
  Result<std::unique_ptr<TerrainRenderer>> renderer =
      makeRenderer(options.algo, inputs, options.renderers);
  if (!renderer) return fail(renderer.error());
  SnapshotOptions snapshot;
  snapshot.width = width;
  snapshot.height = height;
  snapshot.samples = options.look.samples;
  snapshot.settings = renderSettingsOf(options.look);
  snapshot.settings.sky = globe;  // the atmosphere behind the globe
  // A still pages in all the imagery it shows (its passes are not frames of a flight).
  ImageryCliOptions stillImagery = options.imagery;
  stillImagery.uploadsPerFrame = 4096;
  Result<std::unique_ptr<ImageryTextures>> imagery =
      makeImagery(stillImagery, globe ? nullptr : &grid.value(), options.dem.inputs.front());
  if (!imagery) return fail(imagery.error());
  snapshot.settings.imagery = imagery->get();
  FrameStats stats;
  if (globe) {
    Result<RgbImage> image = renderGlobeStill(*renderer.value(), *geoCamera, snapshot, &stats);
    if (!image) return fail(image.error());
    if (Status written = writePng(image.value(), options.output); !written)
      return fail(written.error());
    const GeoCamera& c = *geoCamera;
    // What the renderer says of its frame (its own account: windows, imagery...).
    for (const std::string& line : renderer.value()->frameReport()) spdlog::info("{}", line);
    spdlog::info("wrote {} ({}x{}, {} triangles, geo camera {:.6f},{:.6f},{:.1f},{:.2f},{:.2f},"
                 "{:.1f})",
                 options.output, width, height, stats.triangles, c.latDeg, c.lonDeg, c.altitudeM,
                 c.headingDeg, c.pitchDeg, c.fovYDeg);
    return 0;
  }
  Result<RgbImage> image =
      stacks ? renderSnapshot(*renderer.value(),
                              drawnBounds(stackWorldBounds(stacks->front()), snapshot.settings.verticalExaggeration),
                              camera, snapshot, &stats)
             : renderSnapshot(*renderer.value(), grid.value(), camera, snapshot, &stats);
  if (!image) return fail(image.error());
  if (Status written = writePng(image.value(), options.output); !written)
    return fail(written.error());
  spdlog::info("wrote {} ({}x{}, {} triangles, camera {:.1f},{:.1f},{:.1f},{:.2f},{:.2f},{:.1f})",
               options.output, width, height, stats.triangles, camera.position.x, camera.position.y,
               camera.position.z, camera.yawDeg, camera.pitchDeg, camera.fovYDeg);
  return 0;
}

}  // namespace

Command addRenderCommand(CLI::App& app) {
  auto options = std::make_shared<RenderOptions>();
  CLI::App* sub = app.add_subcommand("render", "Render a DEM or tile store to a PNG");
  addDemInputOptions(sub, options->dem, true, InputKinds::AnyTerrain);
  addStoreLevelOption(sub, options->dem);
  sub->add_option("--store-depth", options->storeDepth,
                  "Global stores: draw one region at this depth (default: globe-reference draws "
                  "the store's finest tiles wherever they show)")
      ->check(integerIn(0, GlobalTiling::kMaxDepth));
  sub->add_option("--drape", options->drape,
                  "Globe renderers: a latitude/longitude colour map to drape over the globe "
                  "(NASA Blue Marble: BlueMarbleAlbedo.jpg with its .jgw)");
  sub->add_option("--region", options->region,
                  "Global stores: draw this region (WEST,SOUTH,EAST,NORTH degrees) at one depth, "
                  "the deepest that fits in memory");
  sub->add_option("-o,--output", options->output, "Output PNG file (a still; --path writes --video)");
  sub->add_option("--path", options->path,
                  "Fly a camera path into --video instead of a still: orbit, flyover, walk, a keyframe "
                  ".json; globe renderers: descent, orbit, lowflight, walk or a lat/lon keyframe .json; a "
                  ".tstack also cave");
  sub->add_option("--frames", options->frames,
                  "With --path: frames along it (default: 30 a second of the video: the path's time over --video-speed)")
      ->check(integerIn(2, 100000));
  sub->add_option("--target", options->target,
                  "With --path, globe paths: LAT,LON the descent, walk and lowflight are about (default: "
                  "the highest sample of the finest data)");
  addVideoOptions(sub, options->video);
  sub->add_option("--size", options->size, "Image size WIDTHxHEIGHT in pixels")
      ->capture_default_str();
  auto* camera = sub->add_option(
      "--camera", options->camera,
      "Camera x,y,z,yaw,pitch,fov: metres east and north of the south-west sample, altitude in "
      "metres; compass yaw, pitch (negative = down) and vertical field of view in degrees");
  auto* view =
      sub->add_option("--view", options->view, "Named view: overview (default), oblique, low")
          ->check(CLI::IsMember({"overview", "oblique", "low"}));
  camera->excludes(view);
  auto* geoCamera = sub->add_option(
      "--geo-camera", options->geoCamera,
      "Globe renderers: camera lat,lon,altitude,heading,pitch,fov (degrees; metres above the "
      "WGS84 ellipsoid; heading clockwise from north; pitch negative = down); default: straight "
      "down on the DEM's centre");
  geoCamera->excludes(camera);
  geoCamera->excludes(view);
  sub->add_option("--geoid", options->geoid,
                  "Globe renderers: a geoid grid (EGM96: egm96_15.gtx) to turn heights above the "
                  "geoid into ellipsoidal ones");
  addLookOptions(sub, options->look);
  sub->add_option("--algo", options->algo,
                  rendererHelp() + "; default reference (stacks-full for a .tstack)");
  addRendererOptions(sub, options->renderers);
  addImageryOptions(sub, options->imagery);
  sub->add_option("--context", options->context, "OpenGL context: headless (EGL) or window (GLFW)")
      ->check(CLI::IsMember({"headless", "window"}));
  return {sub, [options] { return runRender(*options); },
          [options] {
            CommandFiles files{options->dem.inputs, nonEmpty({options->output, options->video.file}), {}};
            if (options->path.ends_with(".json")) files.inputs.push_back(options->path);
            files.inputs.insert(files.inputs.end(), options->imagery.files.begin(), options->imagery.files.end());
            addRendererReadFiles(files, localInputPath(options->dem), options->geoid, options->drape,
                                 options->renderers);
            return files;
          }};
}

}  // namespace tellus::cli
