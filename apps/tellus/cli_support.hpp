#pragma once
// Pieces shared by the subcommands: DEM input options, argument parsing, error reporting,
// GL context creation.
#include <functional>
#include <initializer_list>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "bench_entries.hpp"

#include "cli_files.hpp"
#include "terrain_input.hpp"
#include "imagery_cli.hpp"
#include "video_cli.hpp"
#include "tellus/core/result.hpp"
#include "tellus/dem/dem_loader.hpp"
#include "tellus/dem/terrain_generator.hpp"
#include "tellus/gl/gl_context.hpp"
#include "tellus/render/registry/renderer_registry.hpp"
#include "tellus/render/terrain_renderer.hpp"
#include "tellus/tiles/tile_codec.hpp"
#include "tellus/tiles/tile_store.hpp"

namespace tellus::cli {

// A subcommand: its CLI11 parser, what to run when it was chosen (run() returns the exit code)
// and, once parsed, the files it will read and write (checked by main before run()).
struct Command {
  CLI::App* app = nullptr;
  std::function<int()> run;
  std::function<CommandFiles()> files;
};

// Options every command that reads DEMs takes.
struct DemInputOptions {
  std::vector<std::string> inputs;
  std::string encoding = "plain";
  double spacingM = 0.0;  // 0 = from the georeferencing
  int storeLevel = 0;     // which pyramid level to read when the input is a tile store

  // The inputs classified (terrain_input.hpp), read on first use after parsing and kept:
  // every later question about them asks this value, not the files or the server again.
  const TerrainInput& classified() const;

 private:
  mutable std::shared_ptr<const TerrainInput> classification_;
};
// The (first) input when it is a local file, for the files renderers find beside it
// (RendererInputs::inputPath); empty for a URL or no input.
std::filesystem::path localInputPath(const DemInputOptions& options);

// What the positional inputs of a command may be, for its help.
enum class InputKinds {
  DemFiles,    // rasters only (build, bench codecs, stacks build)
  AnyTerrain,  // rasters, a tile store or a global store (file or URL), or a .tstack
};
void addDemInputOptions(CLI::App* app, DemInputOptions& options, bool inputsRequired,
                        InputKinds kinds = InputKinds::DemFiles);
// Adds --level for commands that also read tile stores.
void addStoreLevelOption(CLI::App* app, DemInputOptions& options);
// Opens a flat tile store (a file or a URL) and checks its georeferencing with GDAL (the store
// reader is GDAL-free and checks only the numbers): a CRS that does not parse or a geotransform
// without area is an error naming the store, in every command, not only in verify.
Result<std::shared_ptr<TileStore>> openTileStore(const std::string& path);
// The same for the (single) input, from the container its classification read.
Result<std::shared_ptr<TileStore>> openTileStore(const DemInputOptions& options);
// The input as a global store, from the container its classification read.
Result<std::shared_ptr<GlobalStore>> openGlobalStoreInput(const DemInputOptions& options);

// Loads the DEM files, or one level of a tile store (.tstore) when that is the only input,
// after checking that the grid fits in memory together with `callerBytesPerSample` bytes per
// sample the caller allocates on top (rendererBytesPerSample() for a renderer).
Result<HeightGrid> loadDemInputs(const DemInputOptions& options, double callerBytesPerSample = 0.0);
// The deepest --level a store can have (a pyramid of 2^24 samples a side has 25 levels).
inline constexpr int kMaxStoreLevel = 30;
// Fails when several inputs include a tile store (a store is read alone).
Status checkNoTileStoreInMosaic(const std::vector<std::string>& inputs);
// True when `inputs` is a single tile store (flat or global). Commands with DemInputOptions
// ask options.classified() instead, which reads the input once.
bool isTileStoreInput(const std::vector<std::string>& inputs);

// How a terrain image looks, shared by render and view.
struct LookOptions {
  std::string shading = "lit";
  bool wireframe = false;
  float exaggeration = 1.0f;
  int samples = 4;  // MSAA samples per pixel
};
void addLookOptions(CLI::App* app, LookOptions& options);
// The render settings they give (shading mode, wireframe, exaggeration).
RenderSettings renderSettingsOf(const LookOptions& options);

// The folder of real data that holds all of `files` (paths inside it): $TELLUS_DATA_DIR,
// ../shared/data or shared/data, the first that has them all; empty if none.
std::filesystem::path findSharedData(std::initializer_list<const char*> files);
// The Landsat 9 Kanto scene (seed 001's texture quadtree): $TELLUS_LANDSAT_KANTO, or
// landsat9-kanto/landsat9_kanto_z12_3857.tif in the shared data (findSharedData); empty if none.
std::filesystem::path findLandsatKanto();

// The fractal codec's range options, shared by build and bench codecs.
struct FractalRangeOptions {
  int range = 4;        // smallest range side, samples
  int levels = 1;       // quadtree levels (1: fixed ranges)
  double splitM = 2.0;  // quadtree: fit RMSE above which a range splits, metres
};
void addFractalRangeOptions(CLI::App* app, FractalRangeOptions& options);
// Into the codec's options; `quantumM` converts the split threshold to steps (1: keep metres).
void applyFractalRangeOptions(const FractalRangeOptions& from, FractalOptions& to, double quantumM);

// The non-empty strings of `paths` (options left empty are not files).
std::vector<std::string> nonEmpty(std::vector<std::string> paths);

// --seed of the procedural terrain: 0 to 2^32 - 1 (generate and demo).
void addSeedOption(CLI::App* app, std::uint64_t& seed);

// "a,b,,c" -> {"a", "b", "c"}.
std::vector<std::string> splitList(const std::string& text);

// "1280x720" -> {1280, 720}; each side 1..16384.
Result<std::pair<int, int>> parseImageSize(const std::string& text);

// The CPU's model name from /proc/cpuinfo ("unknown" elsewhere).
std::string cpuModel();

// tellus bench (the renderer part, command_bench_path.cpp).
struct BenchPathOptions {
  DemInputOptions dem;
  std::string algos;  // empty: reference, or stacks-full for a .tstack
  std::string path = "flyover";
  int frames = 60;
  int warmup = 3;
  std::string size = "1280x720";
  std::string json, csv, plots;
  bool quality = false;
  bool errorImages = false;
  // Streaming renderers load everything a frame needs before drawing it, as
  // stills do: their level of detail measured without the lag of streaming.
  bool settle = false;
  bool finish = false;  // PathRunOptions::finishFrames
  RendererSettings renderers;  // every --<family>-* option (renderer_cli_options.hpp)
  int stackEdits = 0;  // .tstack: brush strokes while flying (stack_edit_bench.cpp)
  std::string vary;  // bench: "OPTION=V1,V2,...", each renderer once per value (bench_entries.hpp)
  std::string target;  // globe paths: LAT,LON (default: the data's highest deep point)
  std::string geoid;   // globe renderers: a geoid grid
  VideoCliOptions video;  // --video: the frames as a video (video_cli.hpp)
  ImageryCliOptions imagery;  // --imagery: draped over the terrain (imagery_cli.hpp)
};
void addBenchPathOptions(CLI::App* bench, BenchPathOptions& options);
// The path a renderer flies for --path: "flyover", the default, means the descent on the globe.
std::string pathInWorld(const std::string& path, bool globe);
// render --path: one renderer along a camera path into a video (command_render_path.cpp).
int runRenderAlongPath(const BenchPathOptions& options, const LookOptions& look);
// Every entry (a renderer with its options, bench_entries.hpp) along the options' camera path:
// the globe's (a globe renderer; "flyover" means the descent there), over a .tstack, or over
// the flat world's DEM or store. Each run is reported under its entry's label, in `entries`'
// order but for the truth or reference, which runs first.
Result<std::vector<PathRun>> runAlongPath(const BenchPathOptions& options, const PathRunOptions& runOptions,
                                          const std::vector<BenchEntry>& entries);
// Frames a path is drawn in: --frames, or (0) kVideoFramesPerSecond of the video's time (the
// path's time over --video-speed).
inline constexpr double kVideoFramesPerSecond = 30.0;
int framesAlong(const BenchPathOptions& options, double pathSeconds);
// `options` with frameIntervalS for `frames` frames over a path of `pathSeconds`.
PathRunOptions timedAlong(const PathRunOptions& options, double pathSeconds, int frames);
int runBenchPath(const BenchPathOptions& options);

// `--algo all`: every renderer of the table that can run on the input and is not a variant of
// another row (seed-table ablations), in table order.
std::vector<std::string> allRenderersFor(const DemInputOptions& options,
                                         const RendererSettings& settings);

// Checks, before anything is loaded, that `algo` names a renderer and that a renderer which
// streams from a tile store is given one, and one that reads a file of its own (a patch file)
// finds it.
Status checkRendererInput(const std::string& algo, const DemInputOptions& options,
                          const RendererSettings& settings);

// The tile store when the input is one (else nullptr), for the streaming renderers.
Result<std::shared_ptr<const TileStore>> openStoreInput(const DemInputOptions& options);

// Prints "tellus: <message>" on stderr and returns exit code 1.
int fail(const Error& error);

Result<std::unique_ptr<gl::GlContext>> createContext(const std::string& kind);

Command addInfoCommand(CLI::App& app);
Command addRenderCommand(CLI::App& app);
Command addGenerateCommand(CLI::App& app);
Command addDemoCommand(CLI::App& app);
Command addBuildCommand(CLI::App& app);
Command addVerifyCommand(CLI::App& app);
Command addExportCommand(CLI::App& app);
Command addBenchCommand(CLI::App& app);
Command addViewCommand(CLI::App& app);
Command addRenderersCommand(CLI::App& app);

// `tellus verify`'s loop: runs `check` on every tile on all cores (an empty string when the
// tile is good), prints each problem and a summary ("all N tiles good" + `checked`); 0 when
// all are good, else 1.
// Stops at the first read that finds `source` dead (a server that stopped answering: the rest
// would each wait for the same deadline) and says how far it got.
// `acrossTiles`, when given, runs once every tile passed: checks between tiles (a flat store's
// shared edges and nesting, store_consistency.hpp), each problem a line.
int checkEveryTile(const std::string& path, std::span<const TileRecord> records,
                   const std::function<std::string(const TileRecord&)>& check,
                   std::string_view checked, const ByteSource& source,
                   const std::function<std::vector<std::string>()>& acrossTiles = {});

// Prints what `tellus info` says about a tile store.
int printStoreInfo(const DemInputOptions& input);

// The procedural terrain of `tellus generate`, georeferenced in UTM zone 33N.
Result<HeightGrid> generateGeoreferencedTerrain(const TerrainParams& params);

}  // namespace tellus::cli
