#include "cli_support.hpp"

#include "tellus/core/input_file.hpp"

#include "stack_cli.hpp"
#include <cstdlib>
#include <map>

#include "tellus/dem/globe_texture_set.hpp"
#include "tellus/tiles/global_store.hpp"

#include <charconv>
#include <fstream>
#include <sstream>

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include "cli_numbers.hpp"
#include "tellus/core/geotransform_check.hpp"
#include "tellus/dem/georeference_check.hpp"
#include "tellus/core/memory_budget.hpp"
#include "tellus/eval/renderer_registry.hpp"
#include "tellus/tiles/tile_store.hpp"

namespace tellus::cli {

void addDemInputOptions(CLI::App* app, DemInputOptions& options, bool inputsRequired,
                        InputKinds kinds) {
  const char* help =
      kinds == InputKinds::DemFiles
          ? "DEM files (any raster GDAL reads: .hgt, GeoTIFF, PNG, ...); several files are mosaicked"
          : "DEM files (any raster GDAL reads: .hgt, GeoTIFF, PNG, ...; several are mosaicked), a tile "
            "store or a global store (.tstore, a file or an http(s):// URL), or material stacks (.tstack)";
  auto* inputs = app->add_option("inputs", options.inputs, help);
  if (inputsRequired) inputs->required();
  app->add_option("--encoding", options.encoding,
                  "How heights are stored: plain, terrain-rgb (Mapbox) or terrarium (Mapzen)")
      ->check(CLI::IsMember({"plain", "terrain-rgb", "terrarium"}));
  app->add_option("--spacing", options.spacingM,
                  "Ground distance between samples in metres (overrides the georeferencing)")
      ->check(numberIn(kMinSampleSpacingM, kMaxSampleSpacingM));
}

void addStoreLevelOption(CLI::App* app, DemInputOptions& options) {
  app->add_option("--level", options.storeLevel,
                  "Pyramid level to use when the input is a tile store (0 = full resolution)")
      ->check(integerIn(0, kMaxStoreLevel));
}

void addSeedOption(CLI::App* app, std::uint64_t& seed) {
  app->add_option("--seed", seed, "Random seed of the terrain")
      ->check(integerIn(0, 4294967295))
      ->capture_default_str();
}

std::vector<std::string> nonEmpty(std::vector<std::string> paths) {
  std::erase_if(paths, [](const std::string& p) { return p.empty(); });
  return paths;
}

std::vector<std::string> splitList(const std::string& text) {
  std::vector<std::string> items;
  std::stringstream stream(text);
  for (std::string item; std::getline(stream, item, ',');) {
    if (!item.empty()) items.push_back(item);
  }
  return items;
}

void addLookOptions(CLI::App* app, LookOptions& options) {
  app->add_option("--shading", options.shading,
                  "lit (hypsometric tints, default), lod (tinted by level of detail) or sse "
                  "(screen-space error of the drawn level, green 0 px to red >= 4 px)")
      ->check(CLI::IsMember({"lit", "lod", "sse"}));
  app->add_flag("--wireframe", options.wireframe, "Overlay the triangle edges");
  app->add_option("--exaggeration", options.exaggeration, "Vertical exaggeration")
      ->check(numberIn(0.01, 100.0))
      ->capture_default_str();
  app->add_option("--samples", options.samples, "MSAA samples per pixel")
      ->check(integerIn(1, 16))
      ->capture_default_str();
}

RenderSettings renderSettingsOf(const LookOptions& options) {
  RenderSettings settings;
  settings.mode = parseShadingMode(options.shading).value();  // checked by addLookOptions
  settings.wireframe = options.wireframe;
  settings.verticalExaggeration = options.exaggeration;
  return settings;
}

void addRingoOptions(CLI::App* app, RingoOptions& options) {
  app->add_option("--ringo-rings", options.rings,
                  "RINGO: rings of blocks around the central 3 x 3 (the seed's test: 4)")
      ->check(integerIn(0, 8))
      ->capture_default_str();
  app->add_option("--ringo-blocks-to-horizon", options.blocksToHorizon,
                  "RINGO: the block size, as the distance to the horizon over this many blocks "
                  "(more: smaller, finer blocks)")
      ->check(numberIn(0.5, 100.0))
      ->capture_default_str();
  app->add_option("--ringo-upload-kib", options.uploadKiBPerFrame,
                  "RINGO: vertex data copied into GPU buffers per frame, KiB")
      ->check(integerIn(1, 1 << 20))
      ->capture_default_str();
  app->add_option("--ringo-threads", options.threads,
                  "RINGO: reorganisation worker threads at most (0: every core)")
      ->check(integerIn(0, 1024))
      ->capture_default_str();
}

std::filesystem::path findBlueMarbleSet() {
  std::vector<std::filesystem::path> candidates;
  if (const char* env = std::getenv("TELLUS_BLUE_MARBLE")) candidates.emplace_back(env);
  candidates.emplace_back("../shared/data/bluemarble8k-global");
  candidates.emplace_back("shared/data/bluemarble8k-global");
  for (const std::filesystem::path& dir : candidates) {
    std::error_code error;
    if (std::filesystem::is_regular_file(dir / kBlueMarbleColour, error)) return dir;
  }
  return {};
}

std::filesystem::path findLandsatKanto() {
  std::vector<std::filesystem::path> candidates;
  if (const char* env = std::getenv("TELLUS_LANDSAT_KANTO")) candidates.emplace_back(env);
  for (const char* data : {"../shared/data", "shared/data"}) {
    candidates.push_back(std::filesystem::path(data) / "landsat9-kanto/landsat9_kanto_z12_3857.tif");
  }
  for (const std::filesystem::path& file : candidates) {
    std::error_code error;
    if (std::filesystem::is_regular_file(file, error)) return file;
  }
  return {};
}

void addSpiralOptions(CLI::App* app, SpiralOptions& options) {
  app->add_option("--spiral-spin-step", options.spinStepDeg,
                  "spiral: spin between vertices, degrees (must divide 360: successive "
                  "revolutions meet)")
      ->check(numberIn(0.1, 120.0))
      ->capture_default_str();
  app->add_option("--spiral-spin-to-double", options.spinToDouble,
                  "spiral: revolutions for the radius to double (the seed's spintodouble)")
      ->check(numberIn(0.05, 100.0))
      ->capture_default_str();
  app->add_option("--spiral-base-radius", options.baseRadiusRad,
                  "spiral: the innermost radius, radians of arc (1e-7: 0.64 m)")
      ->check(numberIn(1e-9, 1e-2))
      ->capture_default_str();
  const std::map<std::string, SpiralProjection> projections{
      {"globe", SpiralProjection::Globe},
      {"flat", SpiralProjection::Flat},
      {"hyperbolic", SpiralProjection::Hyperbolic},
      {"dome", SpiralProjection::Dome}};
  app->add_option("--spiral-projection", options.projection,
                  "spiral: the projection the spiral is wrapped onto")
      ->transform(CLI::CheckedTransformer(projections))
      ->default_str("globe");
  const std::map<std::string, SpiralRadiusMode> modes{{"feedback", SpiralRadiusMode::Feedback},
                                                      {"analytic", SpiralRadiusMode::Analytic}};
  app->add_option("--spiral-radii", options.radiusMode,
                  "spiral: the drawn radii from occlusion-query feedback (the seed's) or "
                  "analytically from the camera")
      ->transform(CLI::CheckedTransformer(modes))
      ->default_str("feedback");
  // The Blue Marble set: found beside the working directory unless given.
  options.texturesDir = findBlueMarbleSet();
  app->add_option("--spiral-textures", options.texturesDir,
                  "spiral: the NASA Blue Marble folder (colour, altitude, clouds, night lights, "
                  "water), converted once to cube maps cached beside the store; 'none': the "
                  "hypsometric tint (default: $TELLUS_BLUE_MARBLE or "
                  "../shared/data/bluemarble8k-global when there)")
      ->transform([](std::string value) { return value == "none" ? std::string() : value; })
      ->capture_default_str();
  app->add_option("--spiral-cube-size", options.cubeFaceSize,
                  "spiral: cube-map texels a face side for the Blue Marble textures")
      ->check(integerIn(16, 8192))
      ->capture_default_str();
  app->add_option_function<std::vector<std::string>>(
         "--spiral-without",
         [&options](const std::vector<std::string>& names) {
           for (const std::string& name : names) {
             if (name == "clouds") options.features &= ~std::uint32_t(kSpiralClouds);
             if (name == "night") options.features &= ~std::uint32_t(kSpiralNightLights);
             if (name == "tangent") options.features &= ~std::uint32_t(kSpiralTangentNormalize);
             if (name == "bump") options.features &= ~std::uint32_t(kSpiralBumpMapping);
             if (name == "specular") options.features &= ~std::uint32_t(kSpiralSpecular);
             if (name == "diffuse") options.features &= ~std::uint32_t(kSpiralDiffuse);
           }
         },
         "spiral: shader features to switch off (the seed's Table 3): clouds, night, tangent "
         "(normalize), bump, specular, diffuse")
      ->delimiter(',')
      ->check(CLI::IsMember({"clouds", "night", "tangent", "bump", "specular", "diffuse"}));
  app->add_flag("--spiral-white", options.whiteShader,
                "spiral: the seed's 'white' fragment shader (Table 1)");
  app->add_flag("--spiral-correct-radius", options.correctRadius,
                "spiral: the seed's square-root radius correction (larger central triangles)");
  app->add_option("--spiral-fan-pixels", options.fanPixels,
                  "spiral: the central fan's target, pixels")
      ->check(numberIn(1.0, 1e6))
      ->capture_default_str();
  app->add_option("--spiral-imagery", options.imagery,
                  "spiral: georeferenced RGB images (GeoTIFF, any CRS; a Landsat scene, decals) "
                  "draped as texture quadtrees driven by occlusion queries, built once into "
                  "STORE.spiral-textures/NAME.timagery; repeat for several, later on top")
      ->check(CLI::ExistingFile);
  app->add_option("--spiral-imagery-transfers", options.imageryOptions.quadtree.maxTransfersPerUpdate,
                  "spiral: texture transfers a frame per image (the seed's smoothing: 1; 0: no "
                  "cap)")
      ->check(integerIn(0, 1000))
      ->capture_default_str();
  app->add_option_function<int>(
         "--spiral-imagery-memory",
         [&options](int mib) {
           options.imageryOptions.quadtree.memoryBudgetBytes = std::uint64_t(mib) << 20;
         },
         "spiral: GPU memory for each image's textures, MiB (default 192)")
      ->check(integerIn(1, 65536));
  app->add_flag("--spiral-imagery-levels", options.imageryOptions.showLevels,
                "spiral: tint the imagery by texel size (the seed's Figure 15: red finest)");
}

void addRagOptions(CLI::App* app, RagOptions& options) {
  app->add_option("--rag-coarse", options.coarseVertices,
                  "RAG: vertices per side of the coarse mesh (the seed measures 20, 40, 80)")
      ->check(integerIn(rag::kMinCoarseVertices, rag::kMaxCoarseVertices))
      ->capture_default_str();
  app->add_option("--rag-passes", options.passes,
                  "RAG: refinement passes per frame (with --rag-adaptive the most)")
      ->check(integerIn(0, kRagMaxPasses))
      ->capture_default_str();
  app->add_flag("--rag-adaptive", options.adaptivePasses,
                "RAG: skip passes that added fewer than 5 % triangles in the previous frame");
  app->add_option("--rag-pixels", options.refinement.pixelEdge,
                  "rag: split an edge whose midpoint moves at least this many pixels on screen")
      ->check(numberIn(0.01, 1000.0))
      ->capture_default_str();
  app->add_option("--rag-height-diff", options.refinement.heightDifferenceM,
                  "rag-right: split an edge whose ends differ by more than this many metres")
      ->check(numberIn(0.0, 100000.0))
      ->capture_default_str();
  app->add_option("--rag-depth-detail", options.refinement.depthDetail,
                  "rag-right: weight of height differences at the far plane, 0 to 1 (1 near)")
      ->check(numberIn(0.0, 1.0))
      ->capture_default_str();
  app->add_flag("--rag-no-clip", [&options](std::int64_t) { options.refinement.earlyClip = false; },
                "RAG: keep triangles outside the view in every pass (no early clipping)");
  app->add_flag("--rag-align", options.alignCoarseMesh,
                "RAG: align the coarse mesh to the samples (cells of a power of two samples, "
                "about --rag-coarse a side), so refinement reaches the map's own samples; for "
                "views from near the ground");
  app->add_option("--rag-max-map", options.maxMapSamples,
                  "RAG: height-map samples a side at most (default: the GPU's texture limit); a "
                  "larger terrain is refined against the finest pyramid level that fits")
      ->check(integerIn(3, 1 << 20));
}

void addRoamOptions(CLI::App* app, RoamOptions& options) {
  roam::RoamSettings& s = options.settings;
  app->add_option("--roam-target", s.targetPx,
                  "roam: error target, pixels (split above it, merge below it)")
      ->check(numberIn(0.01, 1000.0))
      ->capture_default_str();
  app->add_option("--roam-budget", s.triangleBudget, "roam: most triangles (leaves) a frame")
      ->check(integerIn(2, 100000000))
      ->capture_default_str();
  app->add_option("--roam-time", s.timeBudgetMs,
                  "roam: most milliseconds of splits and merges a frame (0: no limit)")
      ->check(numberIn(0.0, 100000.0))
      ->capture_default_str();
  app->add_option("--roam-block", s.blockLog2,
                  "roam: bintree blocks of 2^N cells a side (error bounds are kept per block)")
      ->check(integerIn(2, 10))
      ->capture_default_str();
}

void addGamerOptions(CLI::App* app, GamerOptions& options) {
  gamer::GamerSettings& s = options.settings;
  app->add_option("--gamer-target", s.targetPx, "gamer: error target of the depth tags, pixels")
      ->check(numberIn(0.01, 1000.0))
      ->capture_default_str();
  app->add_option("--gamer-depth", s.maxDepth,
                  "gamer: deepest pattern, 2^N segments a coarse edge (coarse cells of 2^N samples)")
      ->check(integerIn(2, gamer::kMaxPatternDepth))
      ->capture_default_str();
  app->add_flag("--gamer-no-culling", [&options](std::int64_t) { options.settings.culling = false; },
                "gamer: draw every coarse triangle, also outside the view");
}

std::filesystem::path bdamPatchFile(const DemInputOptions& options) {
  if (!options.bdamPatches.empty()) return options.bdamPatches;
  return options.inputs.empty() ? std::filesystem::path() : bdam::defaultPatchFilePath(options.inputs[0]);
}

void addBdamOptions(CLI::App* app, BdamOptions& options, DemInputOptions& dem) {
  app->add_option("--bdam-patches", dem.bdamPatches,
                  "bdam: the patch file (default: NAME.bdam beside the input; 'tellus build --bdam' makes it)");
  app->add_option("--bdam-target", options.selection.targetPx, "bdam: screen-space error target, pixels")
      ->check(numberIn(0.01, 1000.0))
      ->capture_default_str();
  app->add_option("--bdam-cache", options.cacheSlots, "bdam: patches the GPU cache holds at first (grows when a frame needs more)")
      ->check(integerIn(16, 1 << 20))
      ->capture_default_str();
  app->add_flag("--bdam-no-culling", [&options](std::int64_t) { options.selection.culling = false; },
                "bdam: draw every selected patch, also outside the view");
}

void addGiwOptions(CLI::App* app, GiwOptions& options) {
  giw::GiwSettings& s = options.settings;
  app->add_option("--giw-size", s.size, "giw: geometry image side, vertices (the warped quad mesh)")
      ->check(integerIn(9, 2049))
      ->capture_default_str();
  app->add_option("--giw-slope", s.slopeWeight, "giw: importance of steep over flat ground (0: distance and frustum only)")
      ->check(numberIn(0.0, 1000.0))
      ->capture_default_str();
  app->add_option("--giw-uniform", s.uniformShare, "giw: share of each row's and column's samples kept evenly spread")
      ->check(numberIn(0.0, 1.0))
      ->capture_default_str();
}

void addClipmapOptions(CLI::App* app, ClipmapOptions& options) {
  app->add_option("--clipmap-size", options.n,
                  "clipmaps: vertices a level side, 2^k - 1 (31 to 1023)")
      ->check(integerIn(31, 1023))
      ->capture_default_str();
  app->add_option("--clipmap-levels", options.levels,
                  "clipmaps: levels (default: enough for the coarsest to span twice the terrain)")
      ->check(integerIn(1, 24));
  app->add_option("--clipmap-transition", options.transitionWidth,
                  "clipmaps: width of the geomorph band at each level's border, level units "
                  "(default: a fifth of the level size; at most (size + 1) / 4 - 3.5)")
      ->check(numberIn(1.0, 256.0));
  app->add_flag("--clipmap-no-culling", [&options](std::int64_t) { options.culling = false; },
                "clipmaps: draw every block, also outside the view");
}

void addFractalRangeOptions(CLI::App* app, FractalRangeOptions& options) {
  app->add_option("--fractal-range", options.range,
                  "fractal: smallest range block side, 2, 4, 8 or 16 samples (default 4)")
      ->check(integerIn(2, 16));
  app->add_option("--fractal-levels", options.levels,
                  "fractal: quadtree levels; ranges of range << (levels - 1) split down to the "
                  "smallest while their fit is worse than --fractal-split (default 1: no split)")
      ->check(integerIn(1, 8));
  app->add_option("--fractal-split", options.splitM,
                  "fractal: RMSE in metres above which a quadtree range splits (default 2)")
      ->check(numberIn(0.0, 10000.0));
}

void applyFractalRangeOptions(const FractalRangeOptions& from, FractalOptions& to,
                              double quantumM) {
  to.rangeSize = from.range;
  to.quadtreeLevels = from.levels;
  to.splitRmseSteps = from.splitM / quantumM;
}

bool isTileStoreInput(const std::vector<std::string>& inputs) {
  // A URL is always read as a store (DEMs are read from files), so that opening it reports
  // what the server said.
  return inputs.size() == 1 && (isUrl(inputs[0]) || looksLikeTileStore(inputs[0]));
}

Result<HeightGrid> loadDemInputs(const DemInputOptions& options, double callerBytesPerSample) {
  if (isTileStoreInput(options.inputs)) {
    Result<std::shared_ptr<TileStore>> store = openTileStore(options.inputs[0]);
    if (!store) return store.error();
    const PyramidLayout& layout = store.value()->layout();
    if (options.storeLevel < layout.levelCount()) {
      const double samples = double(layout.dataWidthAt(options.storeLevel)) *
                             double(layout.dataHeightAt(options.storeLevel));
      int fits = options.storeLevel;  // the finest level that would fit, for the message
      while (fits + 1 < layout.levelCount() &&
             double(layout.dataWidthAt(fits)) * double(layout.dataHeightAt(fits)) *
                     (kGridBytesPerSample + callerBytesPerSample) >
                 double(availableMemoryBytes())) {
        ++fits;
      }
      if (Status s = checkMemoryFor(
              fmt::format("level {} of '{}' ({} x {} samples)", options.storeLevel,
                          options.inputs[0], layout.dataWidthAt(options.storeLevel),
                          layout.dataHeightAt(options.storeLevel)),
              samples * (kGridBytesPerSample + callerBytesPerSample),
              fmt::format("use a coarser --level (level {} fits) or a streaming renderer "
                          "(--algo rings)",
                          fits));
          !s) {
        return s.error();
      }
    }
    Result<HeightGrid> grid = readStoreLevel(*store.value(), options.storeLevel);
    if (grid && options.spacingM > 0.0) grid->spacingXM = grid->spacingYM = options.spacingM;
    return grid;
  }
  if (Status s = checkNoTileStoreInMosaic(options.inputs); !s) return s.error();
  DemLoadOptions load;
  load.encoding = parseHeightEncoding(options.encoding).value_or(HeightEncoding::Plain);
  if (options.spacingM > 0.0) load.spacingM = options.spacingM;
  load.callerBytesPerSample = callerBytesPerSample;
  std::vector<std::filesystem::path> paths(options.inputs.begin(), options.inputs.end());
  return loadDem(paths, load);
}

Status checkNoTileStoreInMosaic(const std::vector<std::string>& inputs) {
  for (const std::string& input : inputs) {
    if (inputs.size() > 1 && looksLikeTileStore(input)) {
      return makeError("'{}' is a tile store; a store cannot be mosaicked with other inputs",
                       input);
    }
  }
  return {};
}

Status checkRendererInput(const std::string& algo, const DemInputOptions& options) {
  if (!findRenderer(algo)) {
    return makeError("unknown renderer '{}' (available: {})", algo,
                     fmt::join(rendererNames(), ", "));
  }
  const bool stackInput = options.inputs.size() == 1 && isStackFile(options.inputs[0]);
  if (rendererNeedsStacks(algo) != stackInput) {
    return stackInput ? makeError("'{}' holds material stacks: draw it with --algo stacks or stacks-full",
                                  options.inputs[0])
                      : makeError("renderer '{}' draws material stacks: give one .tstack as input "
                                  "(make one with 'tellus stacks build DEM -o NAME.tstack')",
                                  algo);
  }
  if (rendererNeedsStore(algo) && !isTileStoreInput(options.inputs)) {
    return makeError(
        "renderer '{}' streams from a tile store: give one .tstore as input (make "
        "one with 'tellus build DEM... -o NAME.tstore')",
        algo);
  }
  if (algo == "bdam") {
    const std::filesystem::path patches = bdamPatchFile(options);
    std::error_code ec;
    if (!std::filesystem::exists(std::filesystem::symlink_status(patches, ec))) {
      return makeError("renderer 'bdam' draws precomputed patches: {} does not exist (make it with 'tellus build "
                       "DEM... -o NAME.tstore --bdam', or give --bdam-patches FILE)",
                       patches.string());
    }
    if (Status regular = checkRegularInput(patches); !regular) {
      return makeError("renderer 'bdam': the patch file: {}", regular.error().message);
    }
  }
  if (rendererNeedsGlobalStore(algo) &&
      !(isTileStoreInput(options.inputs) && isGlobalStore(options.inputs[0]))) {
    return makeError(
        "renderer '{}' streams from a global store: give one as input (make one with 'tellus "
        "build --global SOURCES... -o earth.tstore')",
        algo);
  }
  return {};
}

std::vector<std::string> allRenderersFor(const DemInputOptions& options) {
  const bool globalStore = isTileStoreInput(options.inputs) && isGlobalStore(options.inputs[0]);
  std::vector<std::string> names;
  for (const RendererEntry& entry : rendererTable()) {
    if (entry.variant) continue;
    if ((entry.world == RendererWorld::Globe) != globalStore) continue;
    if (globalStore && entry.source != RendererSource::GlobalStore) continue;
    if (Status usable = checkRendererInput(std::string(entry.name), options); !usable) {
      // Only BDAM can be missing what a store of the right kind lacks (its patch file): say so.
      if (entry.name == "bdam" && isTileStoreInput(options.inputs)) {
        spdlog::info("--algo all leaves out bdam: {}", usable.error().message);
      }
      continue;
    }
    names.emplace_back(entry.name);
  }
  return names;
}

Result<std::shared_ptr<TileStore>> openTileStore(const std::string& path) {
  Result<std::shared_ptr<TileStore>> store = TileStore::open(path);
  if (!store) return store.error();
  const PyramidLayout& layout = store.value()->layout();
  if (Status georef = checkGeoReference(store.value()->metadata().georef, layout.dataWidth(),
                                        layout.dataHeight());
      !georef) {
    return makeError("'{}': the metadata's georeferencing is unusable: {}", path,
                     georef.error().message);
  }
  return store;
}

Result<std::shared_ptr<const TileStore>> openStoreInput(const DemInputOptions& options) {
  if (!isTileStoreInput(options.inputs)) return std::shared_ptr<const TileStore>();
  Result<std::shared_ptr<TileStore>> store = openTileStore(options.inputs[0]);
  if (!store) return store.error();
  return std::shared_ptr<const TileStore>(store.value());
}

std::string cpuModel() {
  std::ifstream in("/proc/cpuinfo");
  for (std::string line; std::getline(in, line);) {
    if (line.rfind("model name", 0) == 0) return line.substr(line.find(':') + 2);
  }
  return "unknown";
}

Result<std::pair<int, int>> parseImageSize(const std::string& text) {
  const size_t x = text.find_first_of("xX");
  int w = 0, h = 0;
  const char* begin = text.data();
  const char* end = begin + text.size();
  if (x == std::string::npos) return makeError("image size '{}' is not WIDTHxHEIGHT", text);
  const auto [wEnd, wErr] = std::from_chars(begin, begin + x, w);
  const auto [hEnd, hErr] = std::from_chars(begin + x + 1, end, h);
  if (wErr != std::errc() || hErr != std::errc() || wEnd != begin + x || hEnd != end) {
    return makeError("image size '{}' is not WIDTHxHEIGHT", text);
  }
  if (w < 1 || h < 1 || w > 16384 || h > 16384) {
    return makeError("image size '{}': each side must be 1..16384 pixels", text);
  }
  return std::make_pair(w, h);
}

int fail(const Error& error) {
  fmt::print(stderr, "tellus: {}\n", error.message);
  return 1;
}

Result<std::unique_ptr<gl::GlContext>> createContext(const std::string& kind) {
  Result<gl::ContextKind> parsed = gl::parseContextKind(kind);
  if (!parsed) return parsed.error();
  gl::ContextOptions options;
  options.kind = parsed.value();
  options.visibleWindow = false;
  return gl::createGlContext(options);
}

}  // namespace tellus::cli
