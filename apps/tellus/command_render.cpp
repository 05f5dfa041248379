// tellus render: one PNG of a terrain from a camera or a named view.
#include <optional>

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include "cli_support.hpp"
#include "tellus/core/atomic_output.hpp"
#include "tellus/eval/renderer_registry.hpp"
#include "tellus/render/named_views.hpp"
#include "tellus/render/snapshot.hpp"

namespace tellus::cli {
namespace {

struct RenderOptions {
  DemInputOptions dem;
  std::string output;
  std::string size = "1280x720";
  std::string camera;
  std::string view;
  LookOptions look;
  std::string context = "headless";
  std::string algo = "reference";
  RagOptions rag;
};

int runRender(const RenderOptions& options) {
  if (Status s = checkRendererInput(options.algo, options.dem); !s) return fail(s.error());
  Result<std::pair<int, int>> size = parseImageSize(options.size);
  if (!size) return fail(size.error());
  std::optional<Camera> explicitCamera;  // --camera, parsed before the (slow) load
  if (!options.camera.empty()) {
    Result<Camera> parsed = parseCamera(options.camera);
    if (!parsed) return fail(parsed.error());
    explicitCamera = parsed.value();
  }
  if (Status writable = checkOutputWritable(options.output); !writable)
    return fail(writable.error());

  Result<HeightGrid> grid = loadDemInputs(options.dem, rendererBytesPerSample(options.algo));
  if (!grid) return fail(grid.error());
  const auto [width, height] = size.value();
  Camera camera;
  if (explicitCamera) {
    camera = *explicitCamera;
  } else {
    Result<Camera> named = namedView(options.view.empty() ? "overview" : options.view, grid.value(),
                                     double(width) / double(height));
    if (!named) return fail(named.error());
    camera = named.value();
  }

  Result<std::unique_ptr<gl::GlContext>> context = createContext(options.context);
  if (!context) return fail(context.error());
  Result<std::shared_ptr<const TileStore>> store = openStoreInput(options.dem);
  if (!store) return fail(store.error());
  RendererInputs inputs;
  inputs.grid = &grid.value();
  inputs.store = store.value();
  inputs.waitForTiles = true;  // a still waits for every tile it shows
  inputs.rag = options.rag;
  Result<std::unique_ptr<TerrainRenderer>> renderer = makeRenderer(options.algo, inputs);
  if (!renderer) return fail(renderer.error());
  SnapshotOptions snapshot;
  snapshot.width = width;
  snapshot.height = height;
  snapshot.samples = options.look.samples;
  snapshot.settings = renderSettingsOf(options.look);
  FrameStats stats;
  Result<RgbImage> image =
      renderSnapshot(*renderer.value(), grid.value(), camera, snapshot, &stats);
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
  addDemInputOptions(sub, options->dem, true);
  addStoreLevelOption(sub, options->dem);
  sub->add_option("-o,--output", options->output, "Output PNG file")->required();
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
  addLookOptions(sub, options->look);
  sub->add_option("--algo", options->algo, rendererHelp() + "; default reference");
  addRagOptions(sub, options->rag);
  sub->add_option("--context", options->context, "OpenGL context: headless (EGL) or window (GLFW)")
      ->check(CLI::IsMember({"headless", "window"}));
  return {sub, [options] { return runRender(*options); },
          [options] { return CommandFiles{options->dem.inputs, {options->output}, {}}; }};
}

}  // namespace tellus::cli
