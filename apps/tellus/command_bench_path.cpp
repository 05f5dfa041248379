// tellus bench INPUT --algo A[,B...] --path P --frames N: runs each renderer along the same
// camera path in one process, one after another, and reports frame times, triangles and (with
// --quality) screen-space error and cracks: a table, JSON, CSV and plots.
#include <optional>
#include <sstream>
#include <thread>

#include <fmt/format.h>
#include <spdlog/spdlog.h>
#include <nlohmann/json.hpp>

#include "cli_numbers.hpp"
#include "cli_support.hpp"
#include "global_store_cli.hpp"
#include "stack_cli.hpp"
#include "tellus/eval/stack_camera_path.hpp"
#include "tellus/formats/stacks/stack_surface.hpp"
#include "tellus/core/atomic_output.hpp"
#include "tellus/core/child_process.hpp"
#include "tellus/core/scratch_folder.hpp"
#include "tellus/core/progress.hpp"
#include "tellus/eval/bench_report.hpp"
#include "tellus/eval/camera_path.hpp"
#include "renderer_cli_options.hpp"
#include "tellus/gl/gl_info.hpp"

namespace tellus::cli {
namespace fs = std::filesystem;

namespace {

constexpr int kContactSheetFrames = 6;

// Writes the frames each run kept (and their crack and error images) into `folder`; returns the
// report's list of them.
Result<nlohmann::json> writeKeptFrames(const std::vector<PathRun>& runs, const fs::path& folder,
                                       bool errorImages) {
  nlohmann::json files = nlohmann::json::array();
  for (const PathRun& run : runs) {
    for (const KeptFrame& kept : run.kept) {
      const std::string name = fmt::format("frame-{}-{:04}.png", run.algo, kept.index);
      if (Status s = writePng(kept.image, folder / name); !s) return s.error();
      nlohmann::json entry = {{"algo", run.algo}, {"index", kept.index}, {"file", name}};
      if (!kept.cracksMarked.pixels.empty()) {
        const std::string cracks = fmt::format("cracks-{}-{:04}.png", run.algo, kept.index);
        if (Status s = writePng(kept.cracksMarked, folder / cracks); !s) return s.error();
        entry["cracks_file"] = cracks;
      }
      if (errorImages && !kept.errors.pixels.empty()) {
        const std::string errors = fmt::format("error-{}-{:04}.png", run.algo, kept.index);
        if (Status s = writePng(kept.errors, folder / errors); !s) return s.error();
        entry["error_file"] = errors;
      }
      files.push_back(entry);
    }
  }
  return files;
}

// Removes a folder on destruction if it is empty, unless keep() was called.
class EmptyFolderRemover {
 public:
  explicit EmptyFolderRemover(fs::path folder) : folder_(std::move(folder)) {}
  EmptyFolderRemover(const EmptyFolderRemover&) = delete;
  EmptyFolderRemover& operator=(const EmptyFolderRemover&) = delete;
  ~EmptyFolderRemover() {
    std::error_code ec;
    if (!folder_.empty() && fs::is_empty(folder_, ec)) fs::remove(folder_, ec);
  }
  void keep() { folder_.clear(); }

 private:
  fs::path folder_;
};

// Moves every file of `from` into `to` (same file system), each checked like any output: a
// file of the same name that is one of the inputs is never replaced.
Status moveFolderContents(const fs::path& from, const fs::path& to) {
  std::error_code ec;
  for (const fs::directory_entry& entry : fs::directory_iterator(from, ec)) {
    const fs::path destination = to / entry.path().filename();
    if (Status writable = checkOutputWritable(destination); !writable) return writable;
    fs::rename(entry.path(), destination, ec);
    if (ec) return makeError("cannot move '{}' into '{}': {}", entry.path().string(), to.string(), ec.message());
  }
  if (ec) return makeError("cannot list '{}': {}", from.string(), ec.message());
  return {};
}

}  // namespace

Result<std::vector<PathRun>> runStackBench(const BenchPathOptions& o, const PathRunOptions& given,
                                           const std::vector<BenchEntry>& entries);
Result<std::vector<PathRun>> runFlatBench(const BenchPathOptions& o, const PathRunOptions& given,
                                          const std::vector<BenchEntry>& entries);

std::string pathInWorld(const std::string& path, bool globe) {
  return globe && path == "flyover" ? "descent" : path;  // the globe's default path
}

Result<std::vector<PathRun>> runAlongPath(const BenchPathOptions& o, const PathRunOptions& options,
                                          const std::vector<BenchEntry>& entries) {
  if (entries.empty()) return makeError("--algo needs at least one renderer");
  if (rendererDrawsGlobe(entries.front().algo)) {
    BenchPathOptions globeOptions = o;
    globeOptions.path = pathInWorld(o.path, true);
    return runGlobeBench(globeOptions, options, entries);
  }
  if (o.dem.inputs.size() == 1 && isStackFile(o.dem.inputs[0])) return runStackBench(o, options, entries);
  return runFlatBench(o, options, entries);
}

int framesAlong(const BenchPathOptions& o, double pathSeconds) {
  if (o.frames > 0) return o.frames;
  // 30 frames a second of the video, which plays the path video.speed times faster.
  return std::max(2, int(std::ceil(pathSeconds / o.video.speed * kVideoFramesPerSecond)) + 1);
}

PathRunOptions timedAlong(const PathRunOptions& options, double pathSeconds, int frames) {
  PathRunOptions timed = options;
  if (frames > 1 && pathSeconds > 0.0) timed.frameIntervalS = pathSeconds / double(frames - 1);
  return timed;
}

// 3D terrain: every renderer along the same camera path over a .tstack's top surface, judged
// against stacks-full (the ground truth: the whole terrain at its finest level), which runs
// first (and only for its depths and coverage when it is not asked for).
Result<std::vector<PathRun>> runStackBench(const BenchPathOptions& o, const PathRunOptions& given,
                                           const std::vector<BenchEntry>& entries) {
  Result<LoadedStacks> loaded = loadStacks(o.dem.inputs[0], o.imagery.any());
  if (!loaded) return loaded.error();
  const HeightGrid& surface = loaded->surface;  // georeferenced: imagery is placed by it
  const std::vector<StackTerrain>* stacks = &loaded->levels;
  RendererInputs inputs;
  inputs.stacks = stacks;
  // "cave": through the largest cave or arch opening; the other paths over the top surface.
  StackPassage passage;
  Result<CameraPath> path =
      o.path == "cave" ? makeCavePath(stacks->front(), 6.0, &passage) : makeCameraPath(o.path, surface);
  if (!path) return path.error();
  if (o.path == "cave") {
    spdlog::info("cave path: {:.0f} m through a passage of {} stacks, {:.1f} m high on average",
                 passage.lengthM, passage.columns, passage.meanGapM);
  }
  const int frames = framesAlong(o, path->durationS());
  const std::vector<Camera> cameras = path->sample(frames);
  const PathRunOptions options = timedAlong(given, path->durationS(), frames);
  const Aabb bounds = stackWorldBounds(stacks->front());
  constexpr const char* kTruth = "stacks-full";
  // Brush strokes while flying: planned once, applied by every run.
  const std::vector<ScriptedStackEdit> strokes =
      planBenchStrokes(*stacks, cameras, bounds, o.stackEdits);
  if (o.stackEdits > 0) {
    for (const BenchEntry& entry : entries) {
      if (entry.algo != "stacks" && entry.algo != kTruth) {
        return makeError("--stack-edits is for the stack renderers (stacks, stacks-full), not {}",
                         entry.algo);
      }
    }
    spdlog::info("{} brush strokes planned over {} frames", strokes.size(), cameras.size());
  }
  const auto truthRun = [&](const PathRunOptions& runOptions) -> Result<PathRun> {
    if (!strokes.empty()) {
      return runEditedGroundTruth(*stacks, strokes, cameras, bounds, runOptions, o.renderers);
    }
    Result<std::unique_ptr<TerrainRenderer>> truth = makeRenderer(kTruth, inputs, o.renderers);
    if (!truth) return truth.error();
    Progress progress("ground truth (stacks-full)", cameras.size());
    return runDepthTruthPath(*truth.value(), cameras, bounds, runOptions, nullptr, {},
                             [&](int) { progress.advance(); });
  };
  std::vector<BenchEntry> order = entries;
  std::stable_partition(order.begin(), order.end(), [](const BenchEntry& e) { return e.algo == kTruth; });
  std::vector<PathRun> runs;
  CoverageMasks truthCoverage;
  std::vector<DepthImage> truthDepths;
  for (const BenchEntry& entry : order) {
    const std::string& algo = entry.algo;
    if (o.quality && truthDepths.empty() && algo != kTruth) {
      PathRunOptions truthOnly = options;
      truthOnly.keepFrames.clear();
      truthOnly.warmupFrames = 0;
      truthOnly.recordDepths = true;
      truthOnly.frameSink = nullptr;
      Result<PathRun> run = truthRun(truthOnly);
      if (!run) return run.error();
      truthCoverage = std::move(run->coverage);
      truthDepths = std::move(run->depths);
    }
    PathRunOptions runOptions = options;
    runOptions.recordDepths = o.quality && algo == kTruth;
    Result<PathRun> run = makeError("no run");
    if (algo == kTruth && !strokes.empty()) {
      run = truthRun(runOptions);  // made again after each stroke
    } else {
      Result<std::unique_ptr<TerrainRenderer>> renderer = makeRenderer(algo, inputs, entry.settings);
      if (!renderer) return renderer.error();
      StrokeTimings timings;
      if (!strokes.empty()) {
        runOptions.beforeFrame = applyStrokesBeforeFrames(*renderer.value(), strokes, timings);
      }
      // Each renderer starts with no imagery resident, as a fresh process would.
      Result<std::unique_ptr<ImageryTextures>> imagery = makeImagery(o.imagery, &surface, o.dem.inputs.front());
      if (!imagery) return imagery.error();
      runOptions.settings.imagery = imagery->get();
      Progress progress(fmt::format("bench {}", entry.label), cameras.size());
      run = runDepthTruthPath(*renderer.value(), cameras, bounds, runOptions,
                              truthDepths.empty() ? nullptr : &truthDepths, truthCoverage,
                              [&](int) { progress.advance(); });
      if (run) timings.report(run.value());
    }
    if (!run) return run.error();
    if (o.quality && algo == kTruth) {
      truthCoverage = std::move(run->coverage);
      truthDepths = std::move(run->depths);
    }
    run->coverage.clear();
    run->depths.clear();
    run->algo = entry.label;
    runs.push_back(std::move(run.value()));
  }
  return runs;
}

// The flat world's runs: every renderer along the same flat camera path over the DEM or store.
Result<std::vector<PathRun>> runFlatBench(const BenchPathOptions& o, const PathRunOptions& given,
                                          const std::vector<BenchEntry>& entries) {
  double bytesPerSample = o.quality ? rendererBytesPerSample("reference") : 0.0;
  for (const BenchEntry& entry : entries) {
    bytesPerSample = std::max(bytesPerSample, rendererBytesPerSample(entry.algo));
  }
  Result<HeightGrid> grid = loadDemInputs(o.dem, bytesPerSample);
  if (!grid) return grid.error();
  Result<std::shared_ptr<const TileStore>> store = openStoreInput(o.dem);
  if (!store) return store.error();
  RendererInputs inputs;
  inputs.grid = &grid.value();
  inputs.store = store.value();
  inputs.inputPath = localInputPath(o.dem);
  inputs.waitForTiles = o.settle;
  Result<CameraPath> path = makeCameraPath(o.path, grid.value());
  if (!path) return path.error();
  const int frames = framesAlong(o, path->durationS());
  const std::vector<Camera> cameras = path->sample(frames);
  const PathRunOptions options = timedAlong(given, path->durationS(), frames);

  // The reference runs first when asked for, so the others are judged against its coverage.
  std::vector<BenchEntry> order = entries;
  std::stable_partition(order.begin(), order.end(),
                        [](const BenchEntry& e) { return e.algo == "reference"; });
  std::vector<PathRun> runs;
  CoverageMasks referenceCoverage;
  for (const BenchEntry& entry : order) {
    const std::string& algo = entry.algo;
    Result<std::unique_ptr<TerrainRenderer>> renderer = makeRenderer(algo, inputs, entry.settings);
    if (!renderer) return renderer.error();
    if (o.quality && referenceCoverage.empty() && algo != "reference") {
      // No reference run in this bench: render the reference coverage first.
      Result<std::unique_ptr<TerrainRenderer>> reference = makeRenderer("reference", inputs, o.renderers);
      if (!reference) return reference.error();
      PathRunOptions coverageOnly = options;
      coverageOnly.keepFrames.clear();
      coverageOnly.warmupFrames = 0;
      coverageOnly.frameSink = nullptr;
      Progress progress("reference coverage", cameras.size());
      Result<PathRun> coverage = runPath(*reference.value(), cameras, grid.value(), coverageOnly,
                                         {}, [&](int) { progress.advance(); });
      if (!coverage) return coverage.error();
      referenceCoverage = std::move(coverage->coverage);
    }
    // Each renderer starts with no imagery resident, as a fresh process would.
    Result<std::unique_ptr<ImageryTextures>> imagery = makeImagery(o.imagery, &grid.value(), o.dem.inputs.front());
    if (!imagery) return imagery.error();
    PathRunOptions draped = options;
    draped.settings.imagery = imagery->get();
    Progress progress(fmt::format("bench {}", entry.label), cameras.size());
    Result<PathRun> run = runPath(*renderer.value(), cameras, grid.value(), draped,
                                  referenceCoverage, [&](int) { progress.advance(); });
    if (!run) return run.error();
    if (o.quality && algo == "reference") referenceCoverage = run->coverage;
    run->coverage.clear();
    run->algo = entry.label;
    runs.push_back(std::move(run.value()));
  }
  return runs;
}

void addBenchPathOptions(CLI::App* bench, BenchPathOptions& o) {
  addDemInputOptions(bench, o.dem, false, InputKinds::AnyTerrain);
  addStoreLevelOption(bench, o.dem);
  bench->add_option("--algo", o.algos,
                    "Renderers, comma-separated, or 'all' (every renderer that can run on the "
                    "input, one per algorithm; with --plots a comparison chart) (default "
                    "reference; stacks-full for a .tstack). " + rendererHelp());
  bench->add_option("--path", o.path,
                    "orbit, flyover, walk, rotate (seed 004: 360 one-degree turns) or a keyframe "
                    ".json (default flyover); globe renderers: descent, orbit, lowflight, walk or "
                    "a lat/lon keyframe .json (default descent); a .tstack also: cave (through the "
                    "largest cave or arch opening)");
  bench->add_option("--target", o.target,
                    "Globe paths: LAT,LON the descent, walk and lowflight are about (default: "
                    "the highest sample of the finest data)");
  bench->add_option("--geoid", o.geoid,
                    "Globe renderers: a geoid grid (EGM96: egm96_15.gtx) for ellipsoidal heights");
  bench->add_option("--frames", o.frames, "Frames along the path (default 60)")
      ->check(integerIn(1, 100000));
  bench->add_option("--warmup", o.warmup, "Frames drawn before measuring (default 3)")
      ->check(integerIn(0, 1000));
  bench->add_option("--size", o.size, "Frame size WxH (default 1280x720)");
  bench->add_option("--vary", o.vary,
                    "OPTION=V1,V2,...: each renderer whose family has the option (as `tellus "
                    "renderers --options` names it, e.g. stack-updates=40,400,0) runs once per "
                    "value, reported as NAME[OPTION=V], all against the same truth");
  bench->add_option("--json", o.json, "Write the report as JSON here");
  bench->add_option("--csv", o.csv, "Write the per-frame rows as CSV here");
  bench->add_option("--plots", o.plots, "Write PNG charts and a contact sheet into this folder");
  bench->add_flag("--quality", o.quality,
                  "Also measure screen-space error and cracks (reads every frame back)");
  bench->add_flag("--settle", o.settle,
                  "Renderers that stream tiles load all a frame needs before drawing it, "
                  "as stills do: their level of detail without the streaming lag (a path of few "
                  "frames is a time-lapse that no streaming keeps up with)");
  bench->add_flag("--finish", o.finish,
                  "End every frame with glFinish: frame ms is then the whole frame's wall time, "
                  "GPU work included (for drivers whose timer queries miss work, as llvmpipe's "
                  "miss its fragment shading)");
  bench->add_flag("--error-images", o.errorImages,
                  "With --quality and --plots: colour-coded error images of the sampled frames "
                  "(green 0 px to red >= 10 px)");
  addRendererOptions(bench, o.renderers);
  addVideoOptions(bench, o.video);
  addImageryOptions(bench, o.imagery);
  bench->add_option("--stack-edits", o.stackEdits,
                    "A .tstack: this many brush strokes while flying the path (carving and adding "
                    "alternately where the cursor would point), applied by the stacks renderer and "
                    "seen by the ground truth; reports the time from stroke to updated mesh")
      ->check(integerIn(0, 100000));
}

int runBenchPath(const BenchPathOptions& o) {
  if (o.dem.inputs.empty()) {
    return fail(makeError("bench: give a DEM or tile store (or use 'bench codecs')"));
  }
  Result<std::pair<int, int>> size = parseImageSize(o.size);
  if (!size) return fail(size.error());
  const bool stackInput = o.dem.inputs.size() == 1 && isStackFile(o.dem.inputs[0]);
  if (o.stackEdits > 0 && !stackInput) {
    return fail(makeError("--stack-edits edits material stacks: give a .tstack"));
  }
  const std::vector<std::string> algos =
      o.algos == "all" ? allRenderersFor(o.dem, o.renderers)
                       : splitList(o.algos.empty() ? (stackInput ? "stacks-full" : "reference") : o.algos);
  if (algos.empty()) return fail(makeError("--algo needs at least one renderer"));
  for (const std::string& algo : algos) {
    if (Status s = checkRendererInput(algo, o.dem, o.renderers); !s) return fail(s.error());
  }
  const bool globe = rendererDrawsGlobe(algos.front());
  for (const std::string& algo : algos) {
    if (rendererDrawsGlobe(algo) != globe) {
      return fail(makeError("'{}' and '{}' draw different worlds (the globe and the flat "
                            "world): bench them separately",
                            algos.front(), algo));
    }
  }
  if (!globe && (!o.target.empty() || !o.geoid.empty())) {
    return fail(makeError("--target and --geoid are for globe renderers (--algo globe-reference)"));
  }
  Result<std::vector<BenchEntry>> entries = benchEntries(algos, o.renderers, o.vary);
  if (!entries) return fail(entries.error());
  if (o.errorImages && (!o.quality || o.plots.empty())) {
    return fail(makeError("--error-images needs --quality and --plots"));
  }
  for (const std::string& output : {o.json, o.csv}) {
    if (output.empty()) continue;
    if (Status s = checkOutputWritable(output); !s) return fail(s.error());
  }
  std::shared_ptr<PathVideoRecorder> video;
  if (!o.video.file.empty()) {
    Result<std::shared_ptr<PathVideoRecorder>> recorder =
        PathVideoRecorder::create(o.video, benchLabels(entries.value()), size->first, size->second);
    if (!recorder) return fail(recorder.error());
    video = recorder.value();
  }
  // A plots folder this run creates is removed again (when still empty) if the run fails.
  std::optional<EmptyFolderRemover> createdPlots;
  if (!o.plots.empty()) {
    std::error_code ec;
    if (!fs::exists(o.plots, ec)) createdPlots.emplace(fs::path(o.plots));
    fs::create_directories(o.plots, ec);
    if (ec || !fs::is_directory(o.plots)) {
      return fail(makeError("cannot create the plots folder '{}'", o.plots));
    }
  }
  Result<std::unique_ptr<gl::GlContext>> context = createContext("headless");
  if (!context) return fail(context.error());
  const std::string pathName = pathInWorld(o.path, globe);
  const gl::GlInfo info = gl::queryGlInfo();
  BenchContext bench{cpuModel(),   std::thread::hardware_concurrency(),
                     info.vendor,  info.renderer,
                     info.version, o.dem.inputs,
                     pathName,     o.frames,
                     o.warmup,     size->first,
                     size->second, o.quality};
  PathRunOptions options;
  options.width = size->first;
  options.height = size->second;
  options.warmupFrames = o.warmup;
  options.finishFrames = o.finish;
  options.quality = o.quality;
  if (video) options.frameSink = video->sink();
  for (int k = 0; k < kContactSheetFrames; ++k) {
    options.keepFrames.push_back(o.frames == 1 ? 0
                                               : k * (o.frames - 1) / (kContactSheetFrames - 1));
  }
  Result<std::vector<PathRun>> ran = runAlongPath(o, options, entries.value());
  if (!ran) return fail(ran.error());
  std::vector<PathRun> runs = std::move(ran.value());
  if (video) {
    if (Result<std::vector<fs::path>> written = video->finish(); !written) return fail(written.error());
  }
  // Every option of each renderer's family as it ran (given or default), for the report.
  for (PathRun& run : runs) {
    for (const BenchEntry& entry : entries.value()) {
      if (entry.label == run.algo) run.options = rendererOptionValues(entry.algo, entry.settings);
    }
  }

  // Nothing is written unless everything can be: the plots (frames, charts, bench.json) are
  // made in a scratch folder inside the plots folder and moved into it once the plotting
  // script has succeeded, then the JSON and CSV reports are written.
  std::optional<ScratchFolder> staging;
  nlohmann::json keptFiles = nlohmann::json::array();
  if (!o.plots.empty()) {
    Result<ScratchFolder> scratch = ScratchFolder::create(o.plots);
    if (!scratch) return fail(scratch.error());
    staging.emplace(std::move(scratch.value()));
    Result<nlohmann::json> kept = writeKeptFrames(runs, staging->path(), o.errorImages);
    if (!kept) return fail(kept.error());
    keptFiles = std::move(kept.value());
  }
  const nlohmann::json report = benchReportJson(bench, runs, keptFiles);
  fmt::print("{}", benchReportTable(bench, runs));
  const std::string jsonText = report.dump(1) + "\n";
  if (staging) {
    const fs::path reportFile = staging->path() / "bench.json";
    if (Status s = writeTextFileAtomically(reportFile, jsonText); !s) return fail(s.error());
    // An argument vector, no shell: the folder's name is passed as it is, whatever it holds.
    if (Status plotted = runChildProcess({"/usr/bin/python3", TELLUS_PLOT_SCRIPT,
                                          reportFile.string(), staging->path().string()});
        !plotted) {
      return fail(makeError("the plotting script failed ({}); is python3-matplotlib installed?",
                            plotted.error().message));
    }
  }
  if (!o.json.empty()) {
    if (Status s = writeTextFileAtomically(o.json, jsonText); !s) return fail(s.error());
  }
  if (!o.csv.empty()) {
    if (Status s = writeTextFileAtomically(o.csv, benchReportCsv(runs, o.quality)); !s)
      return fail(s.error());
  }
  if (staging) {
    if (Status s = moveFolderContents(staging->path(), o.plots); !s) return fail(s.error());
  }
  if (createdPlots) createdPlots->keep();
  return 0;
}

}  // namespace tellus::cli
