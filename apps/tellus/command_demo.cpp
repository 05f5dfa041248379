// tellus demo: the main job. Generates a procedural terrain, renders a few views with the
// reference renderer and the oblique view with RAG (lit and its screen-space error), and
// writes them with an HTML and a Markdown index.
#include <chrono>
#include <map>
#include <tuple>
#include <filesystem>
#include <glm/glm.hpp>

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include "cli_numbers.hpp"
#include "cli_support.hpp"
#include "tellus/core/atomic_output.hpp"
#include "tellus/dem/geotiff_writer.hpp"
#include "tellus/gl/gl_info.hpp"
#include "tellus/eval/renderer_registry.hpp"
#include "tellus/render/named_views.hpp"
#include "tellus/render/snapshot.hpp"

namespace tellus::cli {
namespace {
namespace fs = std::filesystem;

struct DemoOptions {
  std::string outputDir = "demo-out";
  TerrainParams terrain{.size = 1025, .seed = 7};
  std::string imageSize = "1280x720";
};

struct DemoView {
  std::string file;
  std::string title;
  Camera camera;
  bool wireframe = false;
  std::string algo = "reference";  // a renderer of the registry (drawn from the height grid)
  ShadingMode mode = ShadingMode::Lit;
};

struct RenderedView {
  DemoView view;
  FrameStats stats;
  double milliseconds = 0.0;
};

std::string cameraString(const Camera& c) {
  return fmt::format("{:.1f},{:.1f},{:.1f},{:.2f},{:.2f},{:.1f}", c.position.x, c.position.y,
                     c.position.z, c.yawDeg, c.pitchDeg, c.fovYDeg);
}

// A close-up of the highest peak, seen from the south-west at a slant, with the mesh drawn.
Camera peakCloseUp(const HeightGrid& grid) {
  size_t best = 0;
  for (size_t i = 1; i < grid.heights.size(); ++i) {
    if (grid.heights[i] > grid.heights[best]) best = i;
  }
  const int col = int(best % size_t(grid.width)), row = int(best / size_t(grid.width));
  const glm::dvec3 peak(col * grid.spacingXM, (grid.height - 1 - row) * grid.spacingYM,
                        grid.heights[best]);
  const double distance = 60.0 * grid.spacingXM;
  const glm::dvec3 eye = peak + glm::dvec3(-0.7 * distance, -0.7 * distance, 0.45 * distance);
  return cameraLookingAt(eye, peak - glm::dvec3(0, 0, 0.15 * distance), 50.0);
}

Status writeIndexes(const fs::path& dir, const DemoOptions& options, const HeightGrid& grid,
                    const std::vector<RenderedView>& views, const std::string& glRenderer) {
  const HeightRange range = grid.heightRange();
  const std::string summary = fmt::format(
      "Procedural terrain: {0} x {0} samples, {1} m spacing ({2:.1f} km across), heights "
      "{3:.0f} to {4:.0f} m, seed {5}. Rendered on {6}.",
      grid.width, options.terrain.spacingM, (grid.width - 1) * grid.spacingXM / 1000.0, range.minM,
      range.maxM, options.terrain.seed, glRenderer);
  std::string html = fmt::format(
      "<!doctype html>\n<html><head><meta charset=\"utf-8\"><title>Tellus demo</title>\n"
      "<style>body{{font-family:sans-serif;max-width:1320px;margin:2em auto;background:#15181c;"
      "color:#dde}} img{{width:100%;border-radius:4px}} code{{color:#9cf}}</style></head><body>\n"
      "<h1>Tellus demo</h1>\n<p>{}</p>\n<p>Terrain: <a href=\"terrain.tif\">terrain.tif</a> "
      "(GeoTIFF, metres)</p>\n",
      summary);
  std::string markdown =
      fmt::format("# Tellus demo\n\n{}\n\nTerrain: `terrain.tif` (GeoTIFF, metres).\n\n", summary);
  for (const RenderedView& r : views) {
    // The same sentence for both indexes; only the code markup differs.
    const auto details = [&](std::string_view open, std::string_view close) {
      return fmt::format("{}{}{}: {} triangles, {} draw calls, {:.0f} ms; camera {}{}{}", open,
                         r.view.algo, close, r.stats.triangles, r.stats.drawCalls,
                         r.milliseconds, open, cameraString(r.view.camera), close);
    };
    html += fmt::format("<h2>{}</h2>\n<img src=\"{}\" alt=\"{}\">\n<p>{}</p>\n", r.view.title,
                        r.view.file, r.view.title, details("<code>", "</code>"));
    markdown += fmt::format("## {}\n\n![{}]({})\n\n{}\n\n", r.view.title, r.view.title, r.view.file,
                            details("`", "`"));
  }
  html += "</body></html>\n";
  for (const auto& [name, text] :
       {std::pair{"index.html", html}, std::pair{"index.md", markdown}}) {
    if (Status written = writeTextFileAtomically(dir / name, text); !written) return written;
  }
  return {};
}

int runDemo(const DemoOptions& options) {
  Result<std::pair<int, int>> size = parseImageSize(options.imageSize);
  if (!size) return fail(size.error());
  const fs::path dir(options.outputDir);
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (ec) return fail(makeError("cannot create folder '{}': {}", dir.string(), ec.message()));

  spdlog::info("generating a {0}x{0} terrain (seed {1})", options.terrain.size,
               options.terrain.seed);
  Result<HeightGrid> grid = generateGeoreferencedTerrain(options.terrain);
  if (!grid) return fail(grid.error());
  if (Status written = writeGeoTiff(grid.value(), dir / "terrain.tif"); !written) {
    return fail(written.error());
  }

  Result<std::unique_ptr<gl::GlContext>> context = createContext("headless");
  if (!context) return fail(context.error());
  const std::string glRenderer = gl::queryGlInfo().renderer;

  const auto [width, height] = size.value();
  const double aspect = double(width) / double(height);
  std::vector<DemoView> views;
  for (const auto& [name, file, title] :
       {std::tuple{"overview", "overview.png", "Overview"},
        std::tuple{"oblique", "oblique.png", "Oblique view from the south-east"},
        std::tuple{"low", "low-altitude.png", "Low altitude, looking north"}}) {
    Result<Camera> camera = namedView(name, *grid, aspect);
    if (!camera) return fail(camera.error());
    views.push_back({file, title, camera.value()});
  }
  views.push_back({"wireframe-peak.png", "The highest peak with its full-resolution mesh",
                   peakCloseUp(*grid), true});
  const Camera oblique = views[1].camera;
  views.push_back({"rag-oblique.png",
                   "RAG (seed 004): the oblique view from an 80 x 80 mesh refined on the GPU",
                   oblique, false, "rag"});
  views.push_back({"rag-oblique-sse.png",
                   "RAG's screen-space error (green 0 px to red 4 px and more)", oblique, false,
                   "rag", ShadingMode::ScreenSpaceError});
  RendererInputs inputs;
  inputs.grid = &grid.value();
  inputs.waitForTiles = true;  // stills
  std::map<std::string, std::unique_ptr<TerrainRenderer>> renderers;
  for (const DemoView& view : views) {
    if (renderers.count(view.algo)) continue;
    Result<std::unique_ptr<TerrainRenderer>> made = makeRenderer(view.algo, inputs);
    if (!made) return fail(made.error());
    renderers[view.algo] = std::move(made.value());
  }
  std::vector<RenderedView> rendered;
  for (const DemoView& view : views) {
    SnapshotOptions snapshot;
    snapshot.width = width;
    snapshot.height = height;
    snapshot.settings.wireframe = view.wireframe;
    snapshot.settings.mode = view.mode;
    FrameStats stats;
    const auto start = std::chrono::steady_clock::now();
    Result<RgbImage> image =
        renderSnapshot(*renderers.at(view.algo), grid.value(), view.camera, snapshot, &stats);
    const double ms =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    if (!image) return fail(image.error());
    if (Status written = writePng(image.value(), dir / view.file); !written)
      return fail(written.error());
    spdlog::info("wrote {} ({:.0f} ms)", (dir / view.file).string(), ms);
    rendered.push_back({view, stats, ms});
  }
  if (Status written = writeIndexes(dir, options, grid.value(), rendered, glRenderer); !written) {
    return fail(written.error());
  }
  spdlog::info("demo ready: open {}", (dir / "index.html").string());
  return 0;
}

}  // namespace

Command addDemoCommand(CLI::App& app) {
  auto options = std::make_shared<DemoOptions>();
  CLI::App* sub = app.add_subcommand("demo", "Generate a terrain and render a gallery of views");
  sub->add_option("-o,--output", options->outputDir, "Output folder")->capture_default_str();
  sub->add_option("--terrain-size", options->terrain.size, "Samples per side of the terrain")
      ->check(integerIn(64, 8193))
      ->capture_default_str();
  addSeedOption(sub, options->terrain.seed);
  sub->add_option("--size", options->imageSize, "Image size WIDTHxHEIGHT")->capture_default_str();
  return {sub, [options] { return runDemo(*options); },
          [options] { return CommandFiles{{}, {}, {options->outputDir}}; }};
}

}  // namespace tellus::cli
