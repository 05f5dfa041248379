// tellus demo: the main job, and the showcase. Generates a procedural terrain, builds a tile
// store from it, renders one view with each compared renderer (reference, rings, RAG; lit and
// with the screen-space error), runs a short `bench --quality` of the three along a flyover;
// then puts the terrain on a procedural planet (a global store of both), renders it from orbit
// and from near the ground and runs `bench --quality` of the globe reference along a descent;
// flies the flyover and the descent into videos; and writes the pictures, the videos, the
// tables and the charts as index.html and index.md.
#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <numbers>
#include <map>
#include <tuple>
#include <filesystem>
#include <fstream>
#include <glm/glm.hpp>

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <spdlog/spdlog.h>

#include "cli_numbers.hpp"
#include "cli_support.hpp"
#include "tellus/formats/bdam/bdam_file.hpp"
#include "tellus/formats/bdam/bdam_patches.hpp"
#include "demo_report.hpp"
#include "globe_still.hpp"
#include "tellus/core/atomic_output.hpp"
#include "tellus/core/memory_budget.hpp"
#include "tellus/core/geodesy.hpp"
#include "tellus/dem/geotiff_writer.hpp"
#include "tellus/eval/camera_path.hpp"
#include "tellus/dem/globe_texture_set.hpp"
#include "tellus/dem/latlon_warper.hpp"
#include "tellus/dem/planet_generator.hpp"
#include "tellus/gl/gl_info.hpp"
#include "tellus/render/registry/renderer_registry.hpp"
#include "tellus/render/output/named_views.hpp"
#include "tellus/render/output/snapshot.hpp"
#include "tellus/tiles/global_store_builder.hpp"
#include "tellus/tiles/pyramid_builder.hpp"
#include "tellus/dem/terrain_generator.hpp"
#include "tellus/render/spiral/spiral_renderer.hpp"
#include "tellus/render/stacks/stacks_lod_renderer.hpp"
#include "tellus/formats/stacks/stack_aggregation.hpp"
#include "tellus/formats/stacks/stack_edit.hpp"
#include "tellus/formats/stacks/stack_file.hpp"
#include "tellus/formats/stacks/stack_generator.hpp"
#include "tellus/formats/stacks/stack_surface.hpp"

namespace tellus::cli {
namespace {
namespace fs = std::filesystem;

struct DemoOptions {
  std::string outputDir = "demo-out";
  TerrainParams terrain{.size = 1025, .seed = 7};
  std::string imageSize = "1280x720";
  int benchFrames = 30;
  std::string benchSize = "960x540";
  int planetColumns = 2160;  // samples around the planet's equator (10 arc-minutes)
  int videoFrames = 180;     // frames of each flythrough (0: none); 6 s at 30 frames a second
};

// The renderers the demo compares: every row of the renderer list that draws heightfields on
// the flat world and is not a variant of another (what `bench --algo all` runs on a store with
// its BDAM patches): the reference and one per algorithm.
std::vector<std::string> comparedRenderers() {
  std::vector<std::string> names;
  for (const RendererEntry* entry : rendererTable()) {
    if (entry->variant || entry->world != RendererWorld::Flat ||
        entry->source == RendererSource::StackTerrain)
      continue;
    names.emplace_back(entry->name);
  }
  return names;
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

// Renders `image` (its file, algo and camera set) with `renderer` into dir; fills its stats.
Status renderStill(TerrainRenderer& renderer, const HeightGrid& grid, const fs::path& dir,
                   int width, int height, ShadingMode mode, bool wireframe, DemoImage& image) {
  SnapshotOptions snapshot;
  snapshot.width = width;
  snapshot.height = height;
  snapshot.settings.wireframe = wireframe;
  snapshot.settings.mode = mode;
  const auto start = std::chrono::steady_clock::now();
  Result<RgbImage> rendered = renderSnapshot(renderer, grid, image.camera, snapshot, &image.stats);
  image.milliseconds =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  if (!rendered) return rendered.error();
  if (Status written = writePng(rendered.value(), dir / image.file); !written) return written;
  spdlog::info("wrote {} ({:.0f} ms)", (dir / image.file).string(), image.milliseconds);
  return {};
}

// Runs `tellus bench DIR/STORE --algo ALGOS --path PATH --quality --plots DIR/FOLDER` with the
// demo's frames and size (its table printed), with `settle` streaming renderers' level of detail
// without their streaming lag (the demo's paths are time-lapses); returns the command line that
// reproduces it.
Result<std::string> runDemoBench(const DemoOptions& options, const fs::path& dir,
                                 const std::string& store, const std::string& algos,
                                 const std::string& path, const std::string& folder,
                                 bool settle = false) {
  BenchPathOptions bench;
  bench.dem.inputs = {(dir / store).string()};
  bench.algos = algos;
  bench.path = path;
  bench.frames = options.benchFrames;
  bench.warmup = 2;
  bench.size = options.benchSize;
  bench.quality = true;
  bench.settle = settle;
  bench.plots = (dir / folder).string();
  const std::string command = fmt::format(
      "tellus bench {} --algo {} --path {} --frames {} --warmup {} --size {} --quality{} --plots {}",
      store, bench.algos, bench.path, bench.frames, bench.warmup, bench.size,
      settle ? " --settle" : "", folder);
  spdlog::info("benchmark: {}", command);
  if (runBenchPath(bench) != 0) return makeError("the benchmark '{}' failed (above)", command);
  return command;
}

// A flythrough: `algo` along `path` over `input` (in the demo folder) into `file`, videoFrames
// frames at the bench's frame size, played so that the video lasts videoFrames / 30 seconds;
// globe paths about `target` (LAT,LON; empty: the data's highest point), `imagery` draped.
struct DemoFlight {
  std::string input, algo, path;
  double pathSeconds = 0.0;
  std::string file, title;
  std::string target = {};
  std::vector<fs::path> imagery = {};
};

Result<DemoVideo> renderDemoFlight(const DemoOptions& options, const fs::path& dir, const DemoFlight& f) {
  BenchPathOptions flight;
  flight.dem.inputs = {(dir / f.input).string()};
  flight.algos = f.algo;
  flight.path = f.path.ends_with(".json") ? (dir / f.path).string() : f.path;  // a keyframe file in the folder
  flight.frames = options.videoFrames;
  flight.size = options.benchSize;
  flight.settle = true;  // every tile a frame needs drawn in it: the flight as it looks at rest
  flight.target = f.target;
  for (const fs::path& image : f.imagery) flight.imagery.files.push_back(image.string());
  flight.video.file = (dir / f.file).string();
  flight.video.speed = f.pathSeconds * kVideoFramesPerSecond / double(options.videoFrames);
  std::string command =
      fmt::format("tellus render {} --algo {} --path {} --frames {} --size {} --video {} --video-speed {:.3g}",
                  f.input, f.algo, f.path, flight.frames, flight.size, f.file, flight.video.speed);
  if (!f.target.empty()) command += " --target " + f.target;
  if (!f.imagery.empty()) {
    command += " --imagery";
    for (const fs::path& image : f.imagery) command += " " + image.string();
  }
  spdlog::info("flythrough: {}", command);
  if (runRenderAlongPath(flight, LookOptions{}) != 0) return makeError("the flythrough '{}' failed (above)", command);
  return DemoVideo{f.file, f.title, command};
}

// The real data the flythroughs with imagery fly over (issue 46): the Korea SRTM tiles, ETOPO5,
// Blue Marble and the Landsat 9 scene under ../shared/data (or shared/data, or
// $TELLUS_DATA_DIR); empty when any is missing (the flights are then over the generated worlds).
fs::path findFlightData() {
  return findSharedData({"srtm3-hgt-east-asia/N37E127.hgt", "etopo5-global/etopo5_int16.tif",
                         "bluemarble8k-global/BlueMarbleAlbedo.jpg",
                         "landsat9-kanto/landsat9_kanto_z12_3857.tif"});
}

// Over the Korea store (the 16 SRTM tiles, built into the demo folder) with the clipmaps (the
// fastest of the renderers that meet the error targets there: the rings take 1 s a frame on
// llvmpipe at this size) and Blue Marble draped: the flyover the benchmark measures, over real
// land and sea.
Result<DemoVideo> koreaImageryFlight(const DemoOptions& options, const fs::path& dir, const fs::path& data) {
  std::vector<fs::path> tiles;
  for (int lat = 34; lat <= 37; ++lat) {
    for (int lon = 126; lon <= 129; ++lon) {
      tiles.push_back(data / "srtm3-hgt-east-asia" / fmt::format("N{}E{}.hgt", lat, lon));
    }
  }
  spdlog::info("building korea.tstore from the 16 SRTM tiles of Korea");
  if (Result<BuildReport> built = buildPyramid(tiles, dir / "korea.tstore", BuildOptions{}); !built) {
    return built.error();
  }
  DemInputOptions input;
  input.inputs = {(dir / "korea.tstore").string()};
  Result<HeightGrid> grid = loadDemInputs(input, 0.0);
  if (!grid) return grid.error();
  Result<CameraPath> flyover = makeCameraPath("flyover", grid.value());
  if (!flyover) return flyover.error();
  return renderDemoFlight(
      options, dir,
      {"korea.tstore", "clipmaps", "flyover", flyover->durationS(), "flight-flat.mp4",
       "Over Korea (SRTM, 16 tiles) with the geometry clipmaps and NASA's Blue Marble draped "
       "(4 km texels), the flyover the benchmark measures",
       "", {data / "bluemarble8k-global/BlueMarbleAlbedo.jpg"}});
}

// From orbit down to Tokyo with RINGO over ETOPO5 (built into the demo folder), Blue Marble and
// the Landsat 9 scene of Kanto (30 m) draped.
Result<DemoVideo> tokyoImageryDescent(const DemoOptions& options, const fs::path& dir, const fs::path& data) {
  spdlog::info("building earth-etopo5.tstore from ETOPO5");
  if (Result<GlobalBuildReport> built =
          buildGlobalStore({data / "etopo5-global/etopo5_int16.tif"}, dir / "earth-etopo5.tstore", {});
      !built) {
    return built.error();
  }
  // A keyframe path (geo_camera_path.hpp): straight down from 20,000 km to 20 km over the city,
  // north up, then on down to 2.5 km over the bay, levelling to look north across it at the
  // city (lower, Landsat's 30 m texels fill the screen with a blur).
  constexpr double kDescentSeconds = 60.0;
  const fs::path path = dir / "descent-tokyo.json";
  const std::string keyframes =
      "{\"keyframes\": [\n"
      "  {\"time\": 0, \"lat\": 35.68, \"lon\": 139.77, \"alt\": 20000000, \"heading\": 0, \"pitch\": -90, \"fov\": 45},\n"
      "  {\"time\": 40, \"lat\": 35.62, \"lon\": 139.79, \"alt\": 20000, \"heading\": 0, \"pitch\": -89, \"fov\": 45},\n"
      "  {\"time\": 60, \"lat\": 35.52, \"lon\": 139.82, \"alt\": 2500, \"heading\": 0, \"pitch\": -20, \"fov\": 50}]}\n";
  if (Status written = writeFileAtomically(path, [&](const fs::path& temp) -> Status {
        std::ofstream out(temp);
        out << keyframes;
        out.close();
        return out ? Status{} : makeError("cannot write '{}'", path.string());
      });
      !written) {
    return written.error();
  }
  return renderDemoFlight(
      options, dir,
      {"earth-etopo5.tstore", "ringo", path.filename().string(), kDescentSeconds, "flight-descent.mp4",
       "From orbit down to 2.5 km over Tokyo Bay with RINGO (seed 002) over ETOPO5, NASA's Blue Marble "
       "and the Landsat 9 scene of Kanto (30 m) draped",
       "",
       {data / "bluemarble8k-global/BlueMarbleAlbedo.jpg", data / "landsat9-kanto/landsat9_kanto_z12_3857.tif"}});
}

// The globe section: the planet as the global source and the terrain as a fine one, stills from
// orbit and from near the terrain (the spiral also with the Blue Marble textures), a benchmark of
// the globe reference, RINGO and the spiral down to the ground.
Result<DemoGlobe> runGlobeDemo(const DemoOptions& options, const fs::path& dir,
                               const HeightGrid& terrainGrid) {
  // Where the terrain lies, and land around it at the height of its edges (else it would stand
  // on the planet's sea floor or sink into a mountain).
  Result<LatLonSource> terrainSource = describeLatLonSource(dir / "terrain.tif");
  if (!terrainSource) return terrainSource.error();
  const LatLonBox& box = terrainSource->sampleBox;
  double edgeSum = 0.0;
  for (int i = 0; i < terrainGrid.width; ++i) {
    edgeSum += double(terrainGrid.at(i, 0)) + terrainGrid.at(i, terrainGrid.height - 1);
  }
  for (int j = 0; j < terrainGrid.height; ++j) {
    edgeSum += double(terrainGrid.at(0, j)) + terrainGrid.at(terrainGrid.width - 1, j);
  }
  const PlanetPlateau plateau{
      .latDeg = 0.5 * (box.southDeg + box.northDeg),
      .lonDeg = 0.5 * (box.westDeg + box.eastDeg),
      .radiusDeg = 0.75 * std::max(box.northDeg - box.southDeg, box.eastDeg - box.westDeg),
      .heightM = edgeSum / (2.0 * (terrainGrid.width + terrainGrid.height))};
  spdlog::info("generating a planet of {} x {} samples", options.planetColumns,
               options.planetColumns / 2);
  const HeightGrid planet = generatePlanet({.columns = options.planetColumns,
                                            .seed = options.terrain.seed,
                                            .highestM = 6000.0,
                                            .plateau = plateau});
  if (Status written = writeGeoTiff(planet, dir / "planet.tif"); !written) return written.error();
  const fs::path storePath = dir / "earth.tstore";
  spdlog::info("building {}", storePath.string());
  Result<GlobalBuildReport> built =
      buildGlobalStore({dir / "planet.tif", dir / "terrain.tif"}, storePath, {});
  if (!built) return built.error();
  const GlobalStoreMetadata& m = built->metadata;
  // Sources come finest first: the terrain, then the planet.
  const GeoBounds& terrain = m.sources.front().bounds;
  const double lat = 0.5 * (terrain.southDeg + terrain.northDeg);
  const double lon = 0.5 * (terrain.westDeg + terrain.eastDeg);
  DemoGlobe globe;
  const HeightRange range = planet.heightRange();
  globe.summary = fmt::format(
      "A procedural planet ({} x {} samples of {:.3f} degrees, heights {:.0f} to {:.0f} m; "
      "planet.tif) with the terrain above placed at {:.3f} N {:.3f} E by its own "
      "georeferencing (the planet is land at the height of the terrain's edges, {:.0f} m, "
      "around it), built into one global store (earth.tstore: depths 0..{}, {} tiles, {}, "
      "built in {:.1f} s). Tiles deeper than the planet's exist only over the terrain.",
      planet.width, planet.height, 360.0 / planet.width, range.minM, range.maxM, lat, lon,
      plateau.heightM,
      m.deepestDepth, built->tiles, formatByteCount(double(built->fileBytes)), built->seconds);

  Result<std::pair<int, int>> size = parseImageSize(options.imageSize);
  if (!size) return size.error();
  const auto [width, height] = size.value();
  // South-west of the terrain by its own size, as high as a third of it above its top, looking
  // at its centre.
  const double extentM = std::max(terrainGrid.width * terrainGrid.spacingXM,
                                  terrainGrid.height * terrainGrid.spacingYM);
  const double clearanceM = terrainGrid.heightRange().maxM + 0.35 * extentM;
  const GeoCamera nearCamera{lat - 0.8 * (box.northDeg - box.southDeg),
                             lon - 0.8 * (box.eastDeg - box.westDeg),
                             clearanceM,
                             45.0,
                             -std::atan2(clearanceM - plateau.heightM, 1.13 * extentM) /
                                 wgs84::kDegree,
                             60.0};
  {
    Result<std::unique_ptr<gl::GlContext>> context = createContext("headless");
    if (!context) return context.error();
    const struct {
      const char* file;
      const char* title;
      GeoCamera camera;
      const char* algo;
      bool blueMarble = false;  // the spiral's Blue Marble shading (when the set is found)
      bool landsat = false;     // the Landsat 9 Kanto scene draped (when found)
    } stills[] = {
        {"globe-orbit.png", "The planet from 12,000 km",
         {lat, lon, 12'000'000.0, 0.0, -90.0, 45.0}, "globe-reference"},
        {"globe-terrain.png", "The terrain on the planet, from the south-west", nearCamera,
         "globe-reference"},
        {"globe-terrain-ringo.png", "The same view drawn by RINGO (seed 002)", nearCamera,
         "ringo"},
        {"globe-terrain-spiral.png", "The same view drawn by the spiral globe (seed 001)",
         nearCamera, "spiral"},
        {"globe-orbit-spiral.png",
         "The spiral globe from 12,000 km with the NASA Blue Marble textures (colour, bump, "
         "clouds, night lights, specular water) over the planet's relief",
         {lat, lon, 12'000'000.0, 0.0, -90.0, 45.0}, "spiral", true},
        {"globe-tokyo-spiral.png",
         "Tokyo from 5 km: the Landsat 9 scene (30 m) draped on the spiral globe as a texture "
         "quadtree driven by occlusion queries (seed 001)",
         {35.62, 139.77, 5000.0, 0.0, -45.0, 50.0}, "spiral", true, true},
    };
    const fs::path landsat = findLandsatKanto();
    const fs::path blueMarble = findBlueMarbleSet();
    Result<std::shared_ptr<GlobalStore>> store = GlobalStore::open(storePath);
    if (!store) return store.error();
    for (const auto& still : stills) {
      RendererInputs inputs;
      RendererSettings settings;
      // Every globe renderer reads the store itself: RINGO and the spiral choose their
      // blocks, the reference its cut of the finest tiles that show.
      if (still.blueMarble && blueMarble.empty()) {
        spdlog::warn("no Blue Marble set found (TELLUS_BLUE_MARBLE): {} skipped", still.file);
        continue;
      }
      if (still.landsat && landsat.empty()) {
        spdlog::warn("no Landsat 9 Kanto scene found (TELLUS_LANDSAT_KANTO): {} skipped", still.file);
        continue;
      }
      inputs.globalStore = store.value();
      inputs.waitForTiles = true;  // a still waits for every block
      SpiralOptions& spiral = settings.as<SpiralOptions>("spiral");
      spiral.texturesDir = still.blueMarble ? blueMarble : fs::path();
      if (still.landsat) spiral.imagery = {landsat};
      Result<std::unique_ptr<TerrainRenderer>> renderer =
          makeRenderer(still.algo, inputs, settings);
      if (!renderer) return renderer.error();
      DemoGlobeImage image{still.file, still.title, still.algo, still.camera, {}, 0.0};
      SnapshotOptions snapshot;
      snapshot.width = width;
      snapshot.height = height;
      const auto start = std::chrono::steady_clock::now();
      Result<RgbImage> rendered =
          renderGlobeStill(*renderer.value(), still.camera, snapshot, &image.stats);
      image.milliseconds = std::chrono::duration<double, std::milli>(
                               std::chrono::steady_clock::now() - start)
                               .count();
      if (!rendered) return rendered.error();
      if (Status written = writePng(rendered.value(), dir / image.file); !written) {
        return written.error();
      }
      spdlog::info("wrote {} ({:.0f} ms)", (dir / image.file).string(), image.milliseconds);
      globe.images.push_back(image);
    }
  }

  globe.benchFolder = "globe-bench";
  Result<std::string> command =
      runDemoBench(options, dir, "earth.tstore", "globe-reference,ringo,spiral", "descent",
                   globe.benchFolder, /*settle=*/true);
  if (!command) return command.error();
  globe.benchCommand = command.value();
  if (options.videoFrames > 0) {
    // Onto Tokyo over real data with imagery when the shared data is there, else onto the
    // generated terrain on the generated planet.
    constexpr double kDescentSeconds = 60.0;  // the built-in descent's duration (geo_camera_path.cpp)
    const fs::path data = findFlightData();
    Result<DemoVideo> video =
        !data.empty() ? tokyoImageryDescent(options, dir, data)
                      : renderDemoFlight(options, dir,
                                         {"earth.tstore", "ringo", "descent", kDescentSeconds,
                                          "flight-descent.mp4",
                                          "From orbit down to 2 m above the terrain's highest point with RINGO (seed 002)"});
    if (!video) return video.error();
    globe.videos.push_back(video.value());
  }
  return globe;
}

// A camera beside an arch, on the lower side, under its deck and looking up into the opening.
Camera archCamera(const StackArch& arch, const HeightGrid& surface) {
  const double s = surface.spacingXM;
  const auto world = [&](int x, int row) { return glm::dvec2(x * s, (surface.height - 1 - row) * s); };
  const glm::dvec2 a = world(arch.x0, arch.y0), b = world(arch.x1, arch.y1);
  const glm::dvec2 middle = 0.5 * (a + b);
  const double span = glm::length(b - a);
  const glm::dvec2 along = (b - a) / span, across(-along.y, along.x);
  const auto groundAt = [&](glm::dvec2 p) {
    const int x = std::clamp(int(std::lround(p.x / s)), 0, surface.width - 1);
    const int row = std::clamp(surface.height - 1 - int(std::lround(p.y / s)), 0, surface.height - 1);
    return double(surface.at(x, row));
  };
  const glm::dvec2 left = middle + across * 0.8 * span, right = middle - across * 0.8 * span;
  const glm::dvec2 eye = groundAt(left) < groundAt(right) ? left : right;
  const double deck = 0.5 * (arch.deckTop0M + arch.deckTop1M);
  const double target = deck - 0.5 * arch.openingM;  // the middle of the opening
  Camera camera;
  camera.position = {eye.x, eye.y, std::max(groundAt(eye) + 3.0, target - 0.3 * arch.openingM)};
  const glm::dvec3 to = glm::dvec3(middle, target) - camera.position;
  camera.yawDeg = std::atan2(to.x, to.y) * 180.0 / std::numbers::pi;
  camera.pitchDeg = std::atan2(to.z, glm::length(glm::dvec2(to))) * 180.0 / std::numbers::pi;
  camera.fovYDeg = 60.0;
  return camera;
}

// The stack-terrain section: a steep terrain at 2 m made material stacks with caves, overhangs
// and arches (as tellus stacks build does), drawn whole by stacks-full from above and beside its
// tallest arch.
Result<DemoStacks> runStacksDemo(const fs::path& dir, int width,
                                 int height) {
  TerrainParams params{.size = 385, .seed = 7};
  params.spacingM = 2.0;
  params.reliefM = 3000.0;
  const HeightGrid grid = generateTerrain(params);
  StackFeatureReport features;
  Result<StackTerrain> stacks = generateStacks(grid, StackGeneratorOptions{}, &features);
  if (!stacks) return stacks.error();
  const std::vector<StackTerrain> levels = buildStackPyramid(StackTerrain(stacks.value()));
  if (Status written = writeStackFile(dir / "stacks.tstack", levels); !written) return written.error();
  Result<std::unique_ptr<gl::GlContext>> context = createContext("headless");
  if (!context) return context.error();
  RendererInputs inputs;
  inputs.stacks = &levels;
  Result<std::unique_ptr<TerrainRenderer>> renderer = makeRenderer("stacks-full", inputs);
  if (!renderer) return renderer.error();
  const auto* full = dynamic_cast<const StacksFullRenderer*>(renderer.value().get());
  DemoStacks section;
  section.summary = fmt::format(
      "A generated terrain of {0} x {0} samples at {1} m ({2:.2f} km across) made material stacks "
      "(rock, soil, grass) with caves, overhangs and {3} arch{4}, written to stacks.tstack ({5} "
      "layers); quadrangulated whole on the GPU ({6} nodes of 17^3 cells, {7} quads) in {8:.1f} s. "
      "Reproduce: tellus stacks build DEM -o t.tstack, then tellus render t.tstack.",
      grid.width, params.spacingM, (grid.width - 1) * params.spacingM / 1000.0,
      features.arches.size(), features.arches.size() == 1 ? "" : "es", stacks->layerCount(),
      full ? full->nodeCount() : 0, full ? full->quadCount() : 0, full ? full->buildSeconds() : 0.0);
  const HeightGrid surface = topSurfaceGrid(stacks.value());
  Result<Camera> oblique = namedView("oblique", surface, double(width) / double(height));
  if (!oblique) return oblique.error();
  std::vector<DemoImage> images{
      {"stacks-oblique.png", "Stack terrain drawn by stacks-full: grass, soil and rock by the "
       "vertices' material weights", "stacks-full", oblique.value(), {}, 0.0, {}}};
  if (!features.arches.empty()) {
    const auto tallest = std::max_element(
        features.arches.begin(), features.arches.end(),
        [](const StackArch& a, const StackArch& b) { return a.openingM < b.openingM; });
    images.push_back({"stacks-arch.png",
                      fmt::format("Under the tallest arch ({:.0f} m opening), a shape no "
                                  "heightfield can hold", tallest->openingM),
                      "stacks-full", archCamera(*tallest, surface), {}, 0.0, {}});
  }
  const Aabb bounds = stackWorldBounds(stacks.value());
  for (DemoImage& image : images) {
    SnapshotOptions snapshot;
    snapshot.width = width;
    snapshot.height = height;
    const auto start = std::chrono::steady_clock::now();
    Result<RgbImage> rendered = renderSnapshot(*renderer.value(), drawnBounds(bounds, 1.0f),
                                               image.camera, snapshot, &image.stats);
    image.milliseconds =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    if (!rendered) return rendered.error();
    if (Status written = writePng(rendered.value(), dir / image.file); !written) return written.error();
    spdlog::info("wrote {} ({:.0f} ms)", (dir / image.file).string(), image.milliseconds);
    section.images.push_back(image);
  }
  // The octree LOD renderer (part 2) on the same views: the levels it chose, the arch, and two
  // brush strokes (a crater carved and a rock added) remade in the next frame.
  renderer.value().reset();
  inputs.waitForTiles = true;  // every mesh of the selection made before the still
  Result<std::unique_ptr<TerrainRenderer>> lod = makeRenderer("stacks", inputs);
  if (!lod) return lod.error();
  auto* octree = dynamic_cast<StacksLodRenderer*>(lod.value().get());
  const Camera archView = images.size() > 1 ? images[1].camera : oblique.value();
  const auto shoot = [&](DemoImage image, ShadingMode mode) -> Status {
    SnapshotOptions snapshot;
    snapshot.width = width;
    snapshot.height = height;
    snapshot.settings.mode = mode;
    const auto start = std::chrono::steady_clock::now();
    Result<RgbImage> rendered = renderSnapshot(*lod.value(), drawnBounds(bounds, 1.0f),
                                               image.camera, snapshot, &image.stats);
    image.milliseconds =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    if (!rendered) return rendered.error();
    if (Status written = writePng(rendered.value(), dir / image.file); !written) return written;
    spdlog::info("wrote {} ({:.0f} ms)", (dir / image.file).string(), image.milliseconds);
    section.images.push_back(std::move(image));
    return {};
  };
  // The levels from above the whole terrain, where several show (the oblique view is close
  // enough for the finest level almost everywhere).
  Result<Camera> overview = namedView("overview", surface, double(width) / double(height));
  if (!overview) return overview.error();
  if (Status shot = shoot({"stacks-lod-levels.png", "The octree LOD renderer (--algo stacks, tau "
                           "10 px) over the whole terrain: each colour a level of the stack MipMap "
                           "(red the finest, then orange, yellow, green), stitched without a crack",
                           "stacks", overview.value(), {}, 0.0, {}},
                          ShadingMode::LevelOfDetail);
      !shot) {
    return shot.error();
  }
  if (Status shot = shoot({"stacks-lod-arch.png", "The same view through the octree renderer: "
                           "the geometric error keeps thin roofs at fine levels", "stacks",
                           archView, {}, 0.0, {}}, ShadingMode::Lit);
      !shot) {
    return shot.error();
  }
  // Two strokes where the viewer's brush would land under the cursor at two points of the
  // picture: a crater carved, and a rock added half sunk into the ground.
  const ViewSetup view = ViewSetup::create(oblique.value(), drawnBounds(bounds, 1.0f), width, height);
  const std::array<std::pair<glm::dvec2, SphereEdit>, 2> strokes{
      std::pair{glm::dvec2{0.45 * width, 0.7 * height}, SphereEdit{0, 0, 0, 25.0, kAir}},
      std::pair{glm::dvec2{0.65 * width, 0.62 * height}, SphereEdit{0, 0, 0, 18.0, kStackRock}}};
  for (auto [pixel, edit] : strokes) {
    const glm::dvec3 origin = view.camera.position;
    const std::optional<glm::dvec3> hit = firstSolidAlongRay(
        octree->pyramid().front(), origin,
        glm::normalize(view.unprojectPixel(pixel, 0.5) - origin), view.clip.farM);
    if (!hit) continue;
    edit.xM = hit->x;
    edit.yM = hit->y;
    edit.zM = hit->z - (edit.material == kAir ? 0.0 : 0.5 * edit.radiusM);
    if (Result<StacksEditReport> report = octree->applyEdit(edit); !report) return report.error();
  }
  if (Status shot = shoot({"stacks-lod-edit.png", "Two brush strokes (a crater carved, a rock "
                           "added) at the centre: every mesh they touch, all levels, remade in the "
                           "next frame", "stacks", oblique.value(), {}, 0.0, {}}, ShadingMode::Lit);
      !shot) {
    return shot.error();
  }
  return section;
}

int runDemo(const DemoOptions& options) {
  Result<std::pair<int, int>> size = parseImageSize(options.imageSize);
  if (!size) return fail(size.error());
  if (Result<std::pair<int, int>> benchSize = parseImageSize(options.benchSize); !benchSize) {
    return fail(benchSize.error());
  }
  const fs::path dir(options.outputDir);
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (ec) return fail(makeError("cannot create folder '{}': {}", dir.string(), ec.message()));

  // 1. The terrain, as a GeoTIFF and as a tile store.
  spdlog::info("generating a {0}x{0} terrain (seed {1})", options.terrain.size,
               options.terrain.seed);
  Result<HeightGrid> generated = generateGeoreferencedTerrain(options.terrain);
  if (!generated) return fail(generated.error());
  if (Status written = writeGeoTiff(generated.value(), dir / "terrain.tif"); !written) {
    return fail(written.error());
  }
  const fs::path storePath = dir / "terrain.tstore";
  spdlog::info("building {}", storePath.string());
  Result<BuildReport> built = buildPyramid({dir / "terrain.tif"}, storePath, BuildOptions{});
  if (!built) return fail(built.error());
  // Every renderer reads the store's level 0 (the heights as stored, to 1 cm), so all of them
  // and the error metric see the same surface.
  DemInputOptions storeInput;
  storeInput.inputs = {storePath.string()};
  Result<HeightGrid> grid = loadDemInputs(storeInput, rendererBytesPerSample("reference"));
  if (!grid) return fail(grid.error());
  Result<std::shared_ptr<const TileStore>> store = openStoreInput(storeInput);
  if (!store) return fail(store.error());
  // BDAM's patches beside the store (terrain.bdam), as 'tellus build --bdam' writes them.
  spdlog::info("building BDAM's patches");
  Result<bdam::Hierarchy> patches = bdam::buildHierarchy(grid.value(), bdam::BuildSettings{});
  if (!patches) return fail(patches.error());
  if (Result<std::uint64_t> written = bdam::writePatchFile(patches.value(), bdam::defaultPatchFilePath(storePath));
      !written) {
    return fail(written.error());
  }

  DemoPage page;
  const HeightRange range = grid->heightRange();
  page.terrainSummary = fmt::format(
      "Procedural terrain: {0} x {0} samples, {1} m spacing ({2:.1f} km across), heights "
      "{3:.0f} to {4:.0f} m, seed {5}.",
      grid->width, options.terrain.spacingM, (grid->width - 1) * grid->spacingXM / 1000.0,
      range.minM, range.maxM, options.terrain.seed);
  const StoreMetadata& m = built->metadata;
  page.storeSummary = fmt::format(
      "Tile store: {} levels, {} tiles of {} x {} samples, codec {}, {}, built in {:.1f} s.",
      m.layout.levelCount(), built->tiles, m.layout.samplesPerSide(), m.layout.samplesPerSide(),
      m.codec, formatByteCount(double(built->fileBytes)), built->seconds);

  // 2. Stills: the same view with each renderer, lit and with its error; then a gallery.
  {
    Result<std::unique_ptr<gl::GlContext>> context = createContext("headless");
    if (!context) return fail(context.error());
    page.glRenderer = gl::queryGlInfo().renderer;
    const auto [width, height] = size.value();
    const double aspect = double(width) / double(height);
    RendererInputs inputs;
    inputs.grid = &grid.value();
    inputs.store = store.value();
    inputs.waitForTiles = true;  // stills
    inputs.inputPath = storePath;  // BDAM's patches lie beside the store (NAME.bdam)
    Result<Camera> oblique = namedView("oblique", *grid, aspect);
    if (!oblique) return fail(oblique.error());
    std::map<std::string, std::unique_ptr<TerrainRenderer>> renderers;
    for (const std::string& algo : comparedRenderers()) {
      Result<std::unique_ptr<TerrainRenderer>> made = makeRenderer(algo, inputs);
      if (!made) return fail(made.error());
      const RendererEntry* entry = findRenderer(algo);
      for (const ShadingMode mode : {ShadingMode::Lit, ShadingMode::ScreenSpaceError}) {
        const bool lit = mode == ShadingMode::Lit;
        DemoImage image;
        image.file = fmt::format("{}-oblique{}.png", algo, lit ? "" : "-sse");
        const std::string seed =
            entry->seed == "-" ? std::string() : fmt::format(" (seed {})", entry->seed);
        image.title = lit ? fmt::format("{}{}: {}", algo, seed, entry->description)
                          : fmt::format("{}: screen-space error", algo);
        image.algo = algo;
        image.errorShading = familyOf(*entry).errorShading;
        image.camera = oblique.value();
        if (Status s = renderStill(*made.value(), *grid, dir, width, height, mode, false, image);
            !s) {
          return fail(s.error());
        }
        page.comparison.push_back(image);
      }
      renderers[algo] = std::move(made.value());
    }
    for (const auto& [name, file, title] :
         {std::tuple{"overview", "overview.png", "Overview"},
          std::tuple{"low", "low-altitude.png", "Low altitude, looking north"}}) {
      Result<Camera> camera = namedView(name, *grid, aspect);
      if (!camera) return fail(camera.error());
      DemoImage image{file, title, "reference", camera.value(), {}, 0.0, {}};
      if (Status s = renderStill(*renderers.at("reference"), *grid, dir, width, height,
                                 ShadingMode::Lit, false, image);
          !s) {
        return fail(s.error());
      }
      page.gallery.push_back(image);
    }
    DemoImage peak{"wireframe-peak.png", "The highest peak with its full-resolution mesh",
                   "reference", peakCloseUp(*grid), {}, 0.0, {}};
    if (Status s = renderStill(*renderers.at("reference"), *grid, dir, width, height,
                               ShadingMode::Lit, true, peak);
        !s) {
      return fail(s.error());
    }
    page.gallery.push_back(peak);
  }

  // 3. A short benchmark of the compared renderers with the quality metrics, as `tellus bench`.
  page.benchFolder = "bench";
  Result<std::string> benchCommand =
      runDemoBench(options, dir, "terrain.tstore", "all", "flyover", page.benchFolder);
  if (!benchCommand) return fail(benchCommand.error());
  page.benchCommand = benchCommand.value();

  // Flythroughs: the flat world's flyover with the rings (seed 000), as a video.
  if (options.videoFrames > 0) {
    // Over Korea with Blue Marble when the shared data is there, else over the generated terrain.
    Result<CameraPath> flyover = makeCameraPath("flyover", grid.value());
    if (!flyover) return fail(flyover.error());
    const fs::path data = findFlightData();
    Result<DemoVideo> video =
        !data.empty() ? koreaImageryFlight(options, dir, data)
                      : renderDemoFlight(options, dir,
                                         {"terrain.tstore", "rings", "flyover", flyover->durationS(), "flight-flat.mp4",
                                          "Over the terrain with the rings (seed 000), the flyover the benchmark measures"});
    if (!video) return fail(video.error());
    page.videos.push_back(video.value());
  }

  // 4. Stack terrain (seed 003).
  Result<DemoStacks> stacks = runStacksDemo(dir, size->first, size->second);
  if (!stacks) return fail(stacks.error());
  page.stacks = std::move(stacks.value());

  // 5. The globe.
  Result<DemoGlobe> globe = runGlobeDemo(options, dir, grid.value());
  if (!globe) return fail(globe.error());
  page.globe = std::move(globe.value());

  if (Status written = writeDemoPages(dir, page); !written) return fail(written.error());
  spdlog::info("demo ready: open {}", (dir / "index.html").string());
  return 0;
}

}  // namespace

Command addDemoCommand(CLI::App& app) {
  auto options = std::make_shared<DemoOptions>();
  CLI::App* sub = app.add_subcommand("demo", "Generate a terrain, build a store, compare the renderers: pictures, benchmark, index.html");
  sub->add_option("-o,--output", options->outputDir, "Output folder")->capture_default_str();
  sub->add_option("--terrain-size", options->terrain.size, "Samples per side of the terrain")
      ->check(integerIn(64, 8193))
      ->capture_default_str();
  addSeedOption(sub, options->terrain.seed);
  sub->add_option("--size", options->imageSize, "Image size of the stills WIDTHxHEIGHT")
      ->capture_default_str();
  sub->add_option("--bench-frames", options->benchFrames, "Frames of the benchmark flyover")
      ->check(integerIn(1, 1000))
      ->capture_default_str();
  sub->add_option("--bench-size", options->benchSize, "Frame size of the benchmark WIDTHxHEIGHT")
      ->capture_default_str();
  sub->add_option("--video-frames", options->videoFrames,
                  "Frames of each flythrough video (0: none), at the benchmark's frame size")
      ->check(integerIn(0, 10000))
      ->capture_default_str();
  sub->add_option("--planet-size", options->planetColumns,
                  "Samples around the equator of the procedural planet the terrain is put on")
      ->check(integerIn(64, 8192))
      ->capture_default_str();
  return {sub, [options] { return runDemo(*options); },
          [options] { return CommandFiles{{}, {}, {options->outputDir}}; }};
}

}  // namespace tellus::cli
