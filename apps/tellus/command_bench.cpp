// tellus bench codecs: every Tellus codec and GDAL's GeoTIFF compressors on the same DEM, in
// one run, one thread each (and every core for our encoders): size, error, encode and decode
// speed; then the fractal decoder's convergence and its GPU decoding speed. Table on stdout,
// JSON on request.
#include <algorithm>
#include <thread>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "cli_numbers.hpp"
#include "cli_support.hpp"
#include "tellus/core/atomic_output.hpp"
#include "tellus/core/progress.hpp"
#include "tellus/core/scratch_folder.hpp"
#include "tellus/dem/dem_source.hpp"
#include "tellus/dem/geotiff_peer.hpp"
#include "tellus/gl/gl_context.hpp"
#include "tellus/gl/gl_info.hpp"
#include "tellus/eval/fractal_gpu_benchmark.hpp"
#include "tellus/eval/codec_benchmark.hpp"
#include "tellus/eval/fractal_benchmark.hpp"

namespace tellus::cli {
namespace {

struct BenchCodecsOptions {
  DemInputOptions dem;
  std::string json;
  double maxErrorM = 1.0;
  int tileSize = 256;
  int zstdLevel = kDefaultZstdLevel;
  int repeats = 3;
  int convergenceIterations = 12;
  bool gpu = true;
  FractalRangeOptions fractal;
  std::string codecs;  // comma-separated rows to run (codec names, "gdal"); empty: all
};

struct Entry {
  std::string name;
  std::string kind;  // "tellus" or "gdal"
  std::uint64_t bytes = 0;
  double maxAbsErrorM = 0.0, rmseM = 0.0;
  double encodeSeconds = 0.0, decodeSeconds = 0.0;
  double encodeSecondsAllCores = 0.0;  // 0: not measured
};

// One codec configuration of the table.
struct CodecRun {
  std::string label;
  std::string codec;
  CodecOptions options;
};

// True when `name` is in `selection` (an empty selection selects everything).
bool selected(const std::vector<std::string>& selection, std::string_view name) {
  return selection.empty() ||
         std::find(selection.begin(), selection.end(), name) != selection.end();
}

std::vector<CodecRun> codecRuns(std::uint32_t steps, double maxErrorM, int zstdLevel,
                                const FractalOptions& fractal,
                                const std::vector<std::string>& selection) {
  std::vector<CodecRun> runs;
  for (const std::string& name : codecNames()) {
    if (!selected(selection, name)) continue;
    CodecOptions options{.maxErrorSteps = steps, .zstdLevel = zstdLevel};
    options.fractal = fractal;
    if (name == "fractal") {
      // Pure PIFS (no bound), then with the residual layer that guarantees the bound.
      runs.push_back({"fractal (no bound)", name, options});
      CodecOptions bounded = options;
      bounded.fractal.residual = true;
      runs.push_back({fmt::format("fractal+residual ({} m)", maxErrorM), name, bounded});
    } else {
      const bool lossless = name == "raw" || name == "zstd";
      runs.push_back({lossless ? name : fmt::format("{} ({} m)", name, maxErrorM), name, options});
    }
  }
  return runs;
}

// The fractal codec's payloads of every tile, as one row of the table encoded them.
struct FractalPayloads {
  std::string label;
  bool residual = false;
  std::vector<std::vector<std::byte>> payloads;
};

// The fractal codec's GPU decoder on every tile, when a GL context can be made.
void benchFractalGpuDecode(const std::vector<FractalPayloads>& runs, TileShape shape,
                           double samples, int repeats, nlohmann::json& out) {
  Result<std::unique_ptr<gl::GlContext>> context = createContext("headless");
  if (!context) {
    fmt::print("\nfractal GPU decode: skipped ({})\n", context.error().message);
    return;
  }
  const std::string renderer = gl::queryGlInfo().renderer;
  for (const FractalPayloads& run : runs) {
    Result<FractalGpuDecodeMeasurement> m = measureFractalGpuDecode(run.payloads, shape, repeats);
    if (!m) {
      fmt::print("fractal GPU decode: {}\n", m.error().message);
      return;
    }
    fmt::print(
        "{} on the GPU ({}): {:.1f} M samples/s with parsing and upload, {:.1f} M samples/s "
        "iterating and publishing ({:.1f} iterations per tile)\n",
        run.label, renderer, samples / m->totalSeconds / 1e6, samples / m->gpuSeconds / 1e6,
        m->meanIterations);
    out.push_back(nlohmann::json{{"name", run.label},
                                 {"renderer", renderer},
                                 {"decode_msamples_per_s", samples / m->totalSeconds / 1e6},
                                 {"gpu_msamples_per_s", samples / m->gpuSeconds / 1e6},
                                 {"mean_iterations", m->meanIterations}});
  }
}

int runBenchCodecs(const BenchCodecsOptions& o) {
  if (!o.json.empty()) {
    if (Status s = checkOutputWritable(o.json); !s) return fail(s.error());
  }
  if (o.repeats < 1) return fail(makeError("--repeat must be at least 1"));
  const std::vector<std::string> selection = splitList(o.codecs);
  for (const std::string& name : selection) {
    const std::vector<std::string>& known = codecNames();
    if (name != "gdal" && std::find(known.begin(), known.end(), name) == known.end()) {
      return fail(makeError("--codecs: unknown row '{}' (expected {}, gdal)", name,
                            fmt::join(known, ", ")));
    }
  }
  if (!(o.maxErrorM > 0.0)) return fail(makeError("--max-error must be positive"));
  if (o.dem.classified().isStore()) {
    return fail(makeError("bench codecs takes DEM files, not a tile store"));
  }
  DemLoadOptions load;
  load.encoding = parseHeightEncoding(o.dem.encoding).value_or(HeightEncoding::Plain);
  const std::vector<std::filesystem::path> paths(o.dem.inputs.begin(), o.dem.inputs.end());
  Result<std::unique_ptr<DemSource>> source = DemSource::open(paths, load);
  if (!source) return fail(source.error());
  const double step = source.value()->info().heightStepM;
  Result<HeightGrid> grid = loadDem(paths, load);
  if (!grid) return fail(grid.error());
  const double quantum = step > 0.0 ? step : 0.01;
  if (step > 0.0) {
    // Integer input: the reference is the input as the store keeps it, with interpolated
    // (filled) voids rounded to the quantum like every other sample. Every codec, Tellus' and
    // GDAL's, gets this same grid, so "lossless" means max error 0.
    for (float& h : grid->heights) h = float(std::nearbyint(double(h) / quantum) * quantum);
  }
  const double rounding = step > 0.0 ? 0.0 : 0.5 * quantum;
  const auto steps = std::uint32_t(std::floor((o.maxErrorM - rounding) / quantum + 1e-9));
  const double samples = double(grid->width) * double(grid->height);

  const QuantisedTiles tiles = cutTiles(grid.value(), o.tileSize, quantum);
  // GDAL gets Int16 samples (as SRTM is distributed) when heights are whole metres, with its
  // horizontal integer predictor; otherwise Float32 with its floating-point predictor.
  const bool wholeMetres = step == 1.0;
  const std::string predictor = wholeMetres ? "2" : "3";
  std::vector<Entry> entries;
  FractalOptions fractal;
  applyFractalRangeOptions(o.fractal, fractal, quantum);
  const std::vector<CodecRun> codecs =
      codecRuns(steps, o.maxErrorM, o.zstdLevel, fractal, selection);
  std::vector<GeoTiffPeer> peers = {
      {"gdal-deflate-pred" + predictor, {"COMPRESS=DEFLATE", "PREDICTOR=" + predictor, "ZLEVEL=9"}},
      {"gdal-zstd-pred" + predictor,
       {"COMPRESS=ZSTD", "PREDICTOR=" + predictor, fmt::format("ZSTD_LEVEL={}", o.zstdLevel)}},
      {"gdal-lerc-zstd",
       {"COMPRESS=LERC_ZSTD", fmt::format("MAX_Z_ERROR={}", o.maxErrorM),
        fmt::format("ZSTD_LEVEL={}", o.zstdLevel)}},
  };
  if (!selected(selection, "gdal")) peers.clear();
  Progress progress("bench codecs", codecs.size() + peers.size());
  std::vector<FractalPayloads> fractalRuns;  // kept for the convergence and GPU measurements
  for (const CodecRun& run : codecs) {
    Result<std::unique_ptr<TileCodec>> codec = makeCodec(run.codec, run.options);
    if (!codec) return fail(codec.error());
    Result<CodecMeasurement> m =
        measureCodec(*codec.value(), tiles, grid.value(), quantum, o.repeats);
    if (!m) return fail(m.error());
    entries.push_back({run.label, "tellus", m->bytes, m->maxAbsErrorM, m->rmseM, m->encodeSeconds,
                       m->decodeSeconds, m->encodeSecondsAllCores});
    if (run.codec == "fractal") {
      fractalRuns.push_back({run.label, run.options.fractal.residual, std::move(m->payloads)});
    }
    progress.advance();
  }
  // GDAL's GeoTIFFs go to a private scratch folder (removed at the end, or by the next run
  // when this one is killed).
  Result<ScratchFolder> scratch = ScratchFolder::create();
  if (!scratch) return fail(scratch.error());
  for (const GeoTiffPeer& peer : peers) {
    Result<GeoTiffPeerResult> r =
        measureGeoTiffPeer(grid.value(), wholeMetres, peer, scratch->path(), o.repeats);
    if (!r) return fail(r.error());
    Entry e{peer.name, "gdal", r->bytes, 0.0, 0.0, r->encodeSeconds, r->decodeSeconds};
    if (peer.name.rfind("gdal-lerc", 0) == 0)
      e.name = fmt::format("{} ({} m)", peer.name, o.maxErrorM);
    compareHeights(r->decoded, grid->heights, e.maxAbsErrorM, e.rmseM);
    entries.push_back(e);
    progress.advance();
  }

  fmt::print(
      "{}: {} x {} samples, quantum {} m, {}-cell tiles, one thread, median of {}\n\n",
      o.dem.inputs.size() == 1 ? o.dem.inputs[0] : fmt::format("{} files", o.dem.inputs.size()),
      grid->width, grid->height, quantum, o.tileSize, o.repeats);
  const double tileCount = double(tiles.tiles.size());
  fmt::print("{:<26} {:>12} {:>9} {:>9} {:>10} {:>9} {:>9} {:>10} {:>9}\n", "codec", "bytes",
             "B/tile", "bits/smp", "max err m", "rmse m", "enc MS/s", "enc all", "dec MS/s");
  nlohmann::json rows = nlohmann::json::array();
  for (const Entry& e : entries) {
    const double bits = 8.0 * double(e.bytes) / samples;
    const double enc = samples / e.encodeSeconds / 1e6, dec = samples / e.decodeSeconds / 1e6;
    const double encAll =
        e.encodeSecondsAllCores > 0.0 ? samples / e.encodeSecondsAllCores / 1e6 : 0.0;
    fmt::print("{:<26} {:>12} {:>9} {:>9.3f} {:>10.3f} {:>9.3f} {:>9.1f} {:>10} {:>9.1f}\n", e.name,
               e.bytes,
               e.kind == "tellus" ? fmt::format("{:.0f}", double(e.bytes) / tileCount) : "-", bits,
               e.maxAbsErrorM, e.rmseM, enc, encAll > 0.0 ? fmt::format("{:.1f}", encAll) : "-",
               dec);
    nlohmann::json row = {{"name", e.name},
                          {"kind", e.kind},
                          {"bytes", e.bytes},
                          {"bits_per_sample", bits},
                          {"max_abs_error_m", e.maxAbsErrorM},
                          {"rmse_m", e.rmseM},
                          {"encode_msamples_per_s", enc},
                          {"decode_msamples_per_s", dec}};
    if (e.kind == "tellus") row["bytes_per_tile"] = double(e.bytes) / tileCount;
    if (encAll > 0.0) row["encode_msamples_per_s_all_cores"] = encAll;
    rows.push_back(row);
  }

  // The fractal decoder's convergence from a flat image (no residual layer).
  nlohmann::json convergence = nlohmann::json::array();
  const auto pure = std::find_if(fractalRuns.begin(), fractalRuns.end(),
                                 [](const FractalPayloads& r) { return !r.residual; });
  if (o.convergenceIterations > 0 && pure != fractalRuns.end()) {
    Result<std::vector<ConvergencePoint>> points = measureFractalConvergence(
        pure->payloads, tiles, grid.value(), quantum, o.convergenceIterations);
    if (!points) return fail(points.error());
    const std::string quadtree = o.fractal.levels > 1
                                     ? fmt::format(" split to {}x{} above {} m", o.fractal.range,
                                                   o.fractal.range, o.fractal.splitM)
                                     : "";
    const int largest = o.fractal.range << (o.fractal.levels - 1);
    fmt::print("\nfractal decoding from a flat image ({}x{} ranges{}, no residual):\n", largest,
               largest, quadtree);
    fmt::print("{:>10} {:>9} {:>10} {:>9}\n", "iterations", "rmse m", "max err m", "PSNR dB");
    for (const ConvergencePoint& p : points.value()) {
      fmt::print("{:>10} {:>9.3f} {:>10.3f} {:>9.2f}\n", p.iterations, p.rmseM, p.maxAbsErrorM,
                 p.psnrDb);
      convergence.push_back({{"iterations", p.iterations},
                             {"rmse_m", p.rmseM},
                             {"max_abs_error_m", p.maxAbsErrorM},
                             {"psnr_db", p.psnrDb}});
    }
  }
  nlohmann::json gpu = nlohmann::json::array();
  if (o.gpu && !fractalRuns.empty()) {
    fmt::print("\n");
    benchFractalGpuDecode(fractalRuns, tiles.shape, samples, o.repeats, gpu);
  }
  if (!o.json.empty()) {
    const nlohmann::json report = {
        {"machine",
         {{"cpu", cpuModel()}, {"hardware_threads", std::thread::hardware_concurrency()}}},
        {"inputs", o.dem.inputs},
        {"width", grid->width},
        {"height", grid->height},
        {"samples_note", "bits and speeds are per input sample (width x height)"},
        {"quantum_m", quantum},
        {"tile_size", o.tileSize},
        {"max_error_m", o.maxErrorM},
        {"zstd_level", o.zstdLevel},
        {"repeats", o.repeats},
        {"threads", 1},
        {"entries", rows},
        {"fractal_convergence", convergence},
        {"fractal_gpu_decode", gpu}};
    const std::string text = report.dump(2) + "\n";
    if (Status written = writeTextFileAtomically(o.json, text); !written) {
      return fail(written.error());
    }
  }
  return 0;
}

}  // namespace

Command addBenchCommand(CLI::App& app) {
  CLI::App* bench = app.add_subcommand(
      "bench", "Run renderers along a camera path and measure them (or: bench codecs ...)");
  bench->require_subcommand(0, 1);
  auto paths = std::make_shared<BenchPathOptions>();
  addBenchPathOptions(bench, *paths);
  auto o = std::make_shared<BenchCodecsOptions>();
  CLI::App* codecs = bench->add_subcommand(
      "codecs", "Compare the tile codecs with GDAL's GeoTIFF compressors on a DEM");
  addDemInputOptions(codecs, o->dem, true);
  codecs->add_option("--json", o->json, "Write the results as JSON here");
  codecs->add_option("--max-error", o->maxErrorM, "Bound for the lossy codecs, metres (default 1)")
      ->check(numberIn(0.001, 10000.0));
  codecs->add_option("--tile", o->tileSize, "Cells per tile side (default 256)")
      ->check(CLI::IsMember({16, 32, 64, 128, 256, 512, 1024, 2048, 4096}));
  codecs->add_option("--zstd-level", o->zstdLevel, "zstd level, ours and GDAL's (default 9)")
      ->check(integerIn(1, 22));
  codecs->add_option("--repeat", o->repeats, "Timed repetitions; the median is reported")
      ->check(integerIn(1, 100));
  codecs
      ->add_option("--convergence", o->convergenceIterations,
                   "Fractal decoding: measure iterations 1..N (default 12; 0: skip)")
      ->check(integerIn(0, 32));
  codecs->add_flag("!--no-gpu", o->gpu, "Skip the fractal GPU decoder's measurement");
  codecs->add_option("--codecs", o->codecs,
                     "Rows to run, comma-separated: raw, zstd, bounded, lerc, fractal, gdal "
                     "(GDAL's GeoTIFF compressors); default all");
  addFractalRangeOptions(codecs, o->fractal);
  return {bench,
          [o, paths, codecs]() -> int {
            if (codecs->parsed()) return runBenchCodecs(*o);
            return runBenchPath(*paths);
          },
          [o, paths, codecs]() -> CommandFiles {
            if (codecs->parsed()) return {o->dem.inputs, nonEmpty({o->json}), {}};
            CommandFiles files{paths->dem.inputs, nonEmpty({paths->json, paths->csv, paths->video.file}),
                               nonEmpty({paths->plots})};
            if (paths->path.ends_with(".json")) files.inputs.push_back(paths->path);
            files.inputs.insert(files.inputs.end(), paths->imagery.files.begin(), paths->imagery.files.end());
            addRendererReadFiles(files, localInputPath(paths->dem), paths->geoid, "", paths->renderers);
            return files;
          }};
}

}  // namespace tellus::cli
