#include "cli_support.hpp"

#include "tellus/core/input_file.hpp"

#include "stack_cli.hpp"
#include <algorithm>
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
#include "tellus/tiles/byte_source.hpp"
#include "tellus/render/registry/renderer_registry.hpp"
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

std::filesystem::path findSharedData(std::initializer_list<const char*> files) {
  std::vector<std::filesystem::path> candidates;
  if (const char* env = std::getenv("TELLUS_DATA_DIR")) candidates.emplace_back(env);
  candidates.emplace_back("../shared/data");
  candidates.emplace_back("shared/data");
  for (const std::filesystem::path& data : candidates) {
    std::error_code error;
    const bool all = std::all_of(files.begin(), files.end(), [&](const char* file) {
      return std::filesystem::is_regular_file(data / file, error);
    });
    if (all) return data;
  }
  return {};
}

std::filesystem::path findLandsatKanto() {
  constexpr const char* kScene = "landsat9-kanto/landsat9_kanto_z12_3857.tif";
  if (const char* env = std::getenv("TELLUS_LANDSAT_KANTO")) {
    std::error_code error;
    if (std::filesystem::is_regular_file(env, error)) return env;
  }
  const std::filesystem::path data = findSharedData({kScene});
  return data.empty() ? data : data / kScene;
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

const TerrainInput& DemInputOptions::classified() const {
  if (!classification_) classification_ = std::make_shared<const TerrainInput>(classifyTerrainInput(inputs));
  return *classification_;
}

bool isTileStoreInput(const std::vector<std::string>& inputs) {
  // A URL is always read as a store (DEMs are read from files), so that opening it reports
  // what the server said.
  return inputs.size() == 1 && (isUrl(inputs[0]) || looksLikeTileStore(inputs[0]));
}

Result<HeightGrid> loadDemInputs(const DemInputOptions& options, double callerBytesPerSample) {
  if (options.classified().isStore()) {
    Result<std::shared_ptr<TileStore>> store = openTileStore(options);
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

std::filesystem::path localInputPath(const DemInputOptions& options) {
  if (options.inputs.empty() || isUrl(options.inputs[0])) return {};
  return options.inputs[0];
}

// A file a renderer reads by one of its options (a Path option with besideInputExtension: the
// given file, else NAME.ext beside the input) must be there before anything is loaded.
Status checkRendererOptionFiles(const RendererEntry& entry, const DemInputOptions& options,
                                const RendererSettings& settings) {
  const std::any& values = settings.of(familyNameOf(entry));
  for (const RendererOption& option : familyOf(entry).schema.options) {
    if (option.kind != OptionKind::Path || option.besideInputExtension.empty()) continue;
    const std::filesystem::path file =
        optionPathOrBesideInput(option, values, localInputPath(options));
    std::error_code ec;
    if (file.empty() || !std::filesystem::exists(std::filesystem::symlink_status(file, ec))) {
      return makeError("renderer '{}' reads its {}: {} does not exist ({}; or give {} FILE)",
                       entry.name, option.label, file.empty() ? "none beside a URL" : file.string(),
                       option.help, option.flag);
    }
    if (Status regular = checkRegularInput(file); !regular) {
      return makeError("renderer '{}': the {}: {}", entry.name, option.label,
                       regular.error().message);
    }
  }
  return {};
}

Status checkRendererInput(const std::string& algo, const DemInputOptions& options,
                          const RendererSettings& settings) {
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
  if (rendererNeedsStore(algo) && !options.classified().isStore()) {
    return makeError(
        "renderer '{}' streams from a tile store: give one .tstore as input (make "
        "one with 'tellus build DEM... -o NAME.tstore')",
        algo);
  }
  if (Status files = checkRendererOptionFiles(*findRenderer(algo), options, settings); !files)
    return files;
  if (rendererNeedsGlobalStore(algo) &&
      options.classified().kind != TerrainInputKind::GlobalStore) {
    return makeError(
        "renderer '{}' streams from a global store: give one as input (make one with 'tellus "
        "build --global SOURCES... -o earth.tstore')",
        algo);
  }
  return {};
}

std::vector<std::string> allRenderersFor(const DemInputOptions& options,
                                         const RendererSettings& settings) {
  const bool globalStore = options.classified().kind == TerrainInputKind::GlobalStore;
  std::vector<std::string> names;
  for (const RendererEntry* entry : rendererTable()) {
    if (entry->variant) continue;
    if ((entry->world == RendererWorld::Globe) != globalStore) continue;
    if (globalStore && entry->source != RendererSource::GlobalStore) continue;
    // A store of the right kind can still lack a file a renderer reads beside it (its
    // patches): say so.
    if (Status files = checkRendererOptionFiles(*entry, options, settings); !files) {
      if (options.classified().isStore())
        spdlog::info("--algo all leaves out {}: {}", entry->name, files.error().message);
      continue;
    }
    if (!checkRendererInput(std::string(entry->name), options, settings)) continue;
    names.emplace_back(entry->name);
  }
  return names;
}

namespace {

// The georeferencing check every command makes of a flat store it opened.
Result<std::shared_ptr<TileStore>> checkedTileStore(const std::string& path,
                                                    Result<std::shared_ptr<TileStore>> store) {
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

}  // namespace

Result<std::shared_ptr<TileStore>> openTileStore(const std::string& path) {
  return checkedTileStore(path, TileStore::open(path));
}

Result<std::shared_ptr<TileStore>> openTileStore(const DemInputOptions& options) {
  const TerrainInput& input = options.classified();
  const std::string& path = options.inputs.at(0);
  if (!input.container) return openTileStore(path);  // unreadable: the open says why
  return checkedTileStore(path, TileStore::open(path, *input.container));
}

Result<std::shared_ptr<GlobalStore>> openGlobalStoreInput(const DemInputOptions& options) {
  const TerrainInput& input = options.classified();
  const std::string& path = options.inputs.at(0);
  if (!input.container) return GlobalStore::open(path);
  return GlobalStore::open(path, *input.container);
}

Result<std::shared_ptr<const TileStore>> openStoreInput(const DemInputOptions& options) {
  if (!options.classified().isStore()) return std::shared_ptr<const TileStore>();
  Result<std::shared_ptr<TileStore>> store = openTileStore(options);
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
