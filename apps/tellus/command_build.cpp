// tellus build: DEM inputs -> a tile pyramid store (.tstore).
#include <chrono>

#include <tbb/global_control.h>

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include "cli_numbers.hpp"
#include "cli_support.hpp"
#include "tellus/core/atomic_output.hpp"
#include "tellus/core/memory_budget.hpp"
#include "tellus/mpi/mpi_ranks.hpp"
#include "tellus/tiles/global_store.hpp"
#include "tellus/tiles/global_store_builder.hpp"
#include "tellus/tiles/pyramid_builder.hpp"
#include "tellus/formats/bdam/bdam_file.hpp"
#include "tellus/formats/bdam/bdam_patches.hpp"

namespace tellus::cli {
namespace {

struct BuildCommandOptions {
  DemInputOptions dem;
  std::string output;
  int tileSize = 256;
  std::string codec = "zstd";
  double maxErrorM = 1.0;   // used when --max-error is given
  double quantumM = 0.01;   // used when --quantum is given (else automatic)
  int zstdLevel = kDefaultZstdLevel;
  int threads = 0;  // 0: all cores
  FractalRangeOptions fractal;
  bool global = false;
  int maxDepth = 12;
  bool zeroIsLand = false;  // --global: keep the sources' 0 m samples over a sea floor
  double blendEdgesM = 0.0;  // --global: each partial source fades into the coarser ones, metres
  std::string update;        // --global --update OLD: the store to update with the inputs
  // The options that shape a store's bytes, to tell whether the command line gave them.
  std::vector<const CLI::Option*> shapeOptions;
  bool bdam = false;        // also write BDAM's patch file (NAME.bdam)
  bdam::BuildSettings bdamSettings;
};

// BDAM's patches from level 0 of the store just built at `builtStore` (the grid every renderer
// reads from the store), written into NAME.bdam beside the output store. Returns the exit code.
int buildBdamPatches(const BuildCommandOptions& o, const std::filesystem::path& builtStore) {
  DemInputOptions storeInput;
  storeInput.inputs = {builtStore.string()};
  Result<HeightGrid> grid = loadDemInputs(storeInput);
  if (!grid) return fail(grid.error());
  const auto start = std::chrono::steady_clock::now();
  Result<bdam::Hierarchy> hierarchy = bdam::buildHierarchy(grid.value(), o.bdamSettings);
  if (!hierarchy) return fail(hierarchy.error());
  const std::filesystem::path path = bdam::defaultPatchFilePath(o.output);
  Result<std::uint64_t> bytes = bdam::writePatchFile(hierarchy.value(), path);
  if (!bytes) return fail(bytes.error());
  std::uint64_t triangles = 0;
  for (const bdam::Patch& p : hierarchy->patches) triangles += p.indices.size() / 3;
  fmt::print("{}: BDAM, {} patches on levels 0..{}, {} triangles, {}, built in {:.1f} s\n", path.string(),
             hierarchy->patches.size(), hierarchy->leafLevel, triangles, formatByteCount(double(bytes.value())),
             std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
  return 0;
}

// The store and its BDAM patches, both or neither: the store is built under a temporary name,
// the patches from it, and only once they are written is the store renamed into place.
int buildStoreWithBdam(const std::vector<std::filesystem::path>& inputs, const BuildCommandOptions& o,
                       const BuildOptions& options, BuildReport& report) {
  removeStaleTemporariesFor(o.output);
  const std::filesystem::path temporary = temporaryPathFor(o.output);
  std::error_code ec;
  Result<BuildReport> built = buildPyramid(inputs, temporary, options);
  if (!built) {
    std::filesystem::remove(temporary, ec);
    return fail(built.error());
  }
  report = built.value();
  if (const int code = buildBdamPatches(o, temporary); code != 0) {
    std::filesystem::remove(temporary, ec);
    fmt::print(stderr, "tellus: {} was not written either (a store and its patches are built together)\n",
               o.output);
    return code;
  }
  Status placed = checkOutputWritable(o.output);
  if (placed) {
    std::filesystem::rename(temporary, o.output, ec);
    if (ec) placed = makeError("cannot write '{}': {}", o.output, ec.message());
  }
  if (!placed) {
    std::filesystem::remove(temporary, ec);
    return fail(placed.error());
  }
  return 0;
}

int runGlobalBuild(const BuildCommandOptions& o, const CLI::Option* maxError,
                   const CLI::Option* quantum) {
  GlobalBuildOptions options;
  options.tileCells = o.tileSize;
  options.codec = o.codec;
  if (maxError->count() > 0) options.maxErrorM = o.maxErrorM;
  if (quantum->count() > 0) options.quantumM = o.quantumM;
  options.zstdLevel = o.zstdLevel;
  options.maxDepth = o.maxDepth;
  options.zeroYieldsToSeaFloor = !o.zeroIsLand;
  options.edgeBlendM = o.blendEdgesM;
  if (o.dem.spacingM > 0.0) {
    return fail(makeError("--spacing does not apply to --global builds: every source is placed "
                          "by its own georeferencing"));
  }
  // --encoding says how the 8-bit RGB sources among the inputs encode heights.
  options.rgbEncoding = parseHeightEncoding(o.dem.encoding).value_or(HeightEncoding::Plain);
  std::vector<std::filesystem::path> inputs;
  if (!o.update.empty()) {
    // The store's own sources first, in its order, then the new ones; its options, not the
    // command line's defaults.
    for (const CLI::Option* given : o.shapeOptions) {
      if (given->count() > 0) {
        return fail(makeError("--update keeps the options '{}' was built with: leave out {}",
                              o.update, given->get_name()));
      }
    }
    Result<std::shared_ptr<GlobalStore>> previous = GlobalStore::open(o.update);
    if (!previous) return fail(previous.error());
    const GlobalStoreMetadata& m = previous.value()->metadata();
    options.tileCells = m.tileCells;
    options.codec = m.codec;
    options.zstdLevel = m.zstdLevel;
    options.quantumM = m.quantumM;
    options.zeroYieldsToSeaFloor = m.zeroYieldsToSeaFloor;
    options.edgeBlendM = m.edgeBlendM;
    for (const GlobalStoreSource& source : m.sources) inputs.emplace_back(source.path);
    options.update = GlobalBuildOptions::Update{o.update, inputs.size()};
  }
  inputs.insert(inputs.end(), o.dem.inputs.begin(), o.dem.inputs.end());
  // Under mpirun, every rank runs this; rank 0 speaks for the job (every rank gets the same
  // result, so the others stay quiet).
  Result<std::unique_ptr<Ranks>> ranks = openRanks();
  if (!ranks) return fail(ranks.error());
  const bool speaker = ranks.value()->rank() == 0;
  if (!speaker) spdlog::set_level(spdlog::level::err);
  Result<GlobalBuildReport> report = buildGlobalStore(inputs, o.output, options, ranks->get());
  if (!report) return speaker ? fail(report.error()) : 1;
  if (!speaker) return 0;
  const GlobalStoreMetadata& m = report->metadata;
  fmt::print(
      "{}: global store, depths 0..{}, {} tiles of {}x{} samples from {} sources, codec {}, {} "
      "({:.2f}x smaller than int32 tiles), built in {:.1f} s on {} rank{} ({} subtrees from "
      "depth {})\n",
      o.output, m.deepestDepth, report->tiles, m.tileCells + 1, m.tileCells + 1, m.sources.size(),
      m.codec, formatByteCount(double(report->fileBytes)),
      double(report->decodedBytes) / double(std::max<std::uint64_t>(1, report->payloadBytes)),
      report->seconds, report->ranks, report->ranks > 1 ? "s" : "", report->subtrees,
      report->splitDepth);
  // Where the time went (the slowest rank of each step) and the largest rank's memory: the
  // figures of docs/scale.md.
  GlobalBuildReport::RankFigures most;
  for (const GlobalBuildReport::RankFigures& r : report->perRank) {
    most.rootsS = std::max(most.rootsS, r.rootsS);
    most.coarseS = std::max(most.coarseS, r.coarseS);
    most.subtreesS = std::max(most.subtreesS, r.subtreesS);
    most.joinS = std::max(most.joinS, r.joinS);
    most.peakBytes = std::max(most.peakBytes, r.peakBytes);
  }
  fmt::print("{}: steps (slowest rank): roots {:.1f} s, coarse tiles {:.1f} s, subtrees {:.1f} s, "
             "join {:.1f} s (index {}); peak memory of a rank {}\n",
             o.output, most.rootsS, most.coarseS, most.subtreesS, most.joinS,
             formatByteCount(double(report->indexBytes)), formatByteCount(double(most.peakBytes)));
  if (!o.update.empty()) {
    fmt::print("{}: updated from {}: {} tiles rewritten of {} ({} warped again, {} read back "
               "unchanged, {} made from their children)\n",
               o.output, o.update, report->tilesRewritten, report->tiles, report->tilesWarped,
               report->tilesReadBack,
               report->tiles - report->tilesWarped - report->tilesReadBack);
  }
  if (m.uncoveredSamples > 0) {
    fmt::print("{}: {} stored samples lie outside every source and are 0 m\n", o.output,
               m.uncoveredSamples);
  }
  return 0;
}

}  // namespace

Command addBuildCommand(CLI::App& app) {
  auto o = std::make_shared<BuildCommandOptions>();
  CLI::App* sub = app.add_subcommand("build", "Build a tile pyramid store (.tstore) from DEMs");
  addDemInputOptions(sub, o->dem, true);
  sub->add_option("-o,--output", o->output, "The store to write (NAME.tstore)")->required();
  CLI::Option* tileOption = sub->add_option("--tile", o->tileSize,
                  "Cells per tile side, a power of two (tiles hold N+1 samples)")
      ->check(integerIn(16, PyramidLayout::kMaxTileSize));
  CLI::Option* codecOption = sub->add_option("--codec", o->codec,
                  "Tile codec: raw, zstd (lossless), bounded, lerc or fractal (lossy)");
  CLI::Option* maxError =
      sub->add_option("--max-error", o->maxErrorM,
                      "Lossy codecs: guaranteed max |stored - input| in metres (default 1; "
                      "fractal: adds the residual layer, without it the error is only measured)")
          ->check(numberIn(0.0, 10000.0));
  addFractalRangeOptions(sub, o->fractal);
  CLI::Option* quantum =
      sub->add_option("--quantum", o->quantumM,
                      "Metres per stored integer step (default: the input's own step, or 0.01 "
                      "for floating-point inputs)")
          ->check(numberIn(kMinQuantumM, kMaxQuantumM));
  CLI::Option* zstdOption = sub->add_option("--zstd-level", o->zstdLevel, "zstd level for zstd/bounded, 1..22 (default 9, GDAL's)")
      ->check(integerIn(1, 22));
  sub->add_option("--threads", o->threads, "Worker threads (default: all cores)")
      ->check(integerIn(0, 1024));
  sub->add_flag("--global", o->global,
                "Build a global store: latitude/longitude tiles of the whole Earth from several "
                "georeferenced sources (ETOPO, SRTM HGT, BIL, GeoTIFF...), finest source first");
  CLI::Option* zeroOption = sub->add_flag("--zero-is-land", o->zeroIsLand,
                "--global: keep every source's samples of exactly 0 m (by default they yield to "
                "a coarser source's sea floor there: SRTM stores the sea as 0 m, ETOPO has the "
                "bathymetry)");
  CLI::Option* blendOption = sub->add_option("--blend-edges", o->blendEdgesM,
                  "--global: metres over which each source that does not cover the globe fades "
                  "into the coarser sources inside its edges, so that a fine DEM meets the "
                  "global one without a cliff (default 0: every source up to its edge)")
      ->check(numberIn(0.0, kMaxEdgeBlendM));
  sub->add_option("--max-depth", o->maxDepth,
                  "--global: the deepest tile depth any source feeds (default 12)")
      ->check(integerIn(0, GlobalTiling::kMaxDepth));
  o->shapeOptions = {tileOption, codecOption, zstdOption, quantum, zeroOption, blendOption};
  sub->add_option("--update", o->update,
                  "--global: update this global store with the inputs (new sources): only the "
                  "tiles they reach are warped again, the rest is read back, and the result, "
                  "written to -o (not over it), equals a build of all the sources");
  sub->add_flag("--bdam", o->bdam,
                "Also write BDAM's patch file NAME.bdam beside the store (--algo bdam draws it): TIN "
                "patches on a triangle bintree, simplified from the store's level 0 with locked borders");
  sub->add_option("--bdam-leaf", o->bdamSettings.leafLog2,
                  "--bdam: a leaf patch covers 2^N half-cells of the grid (default 13: 64 x 64 cells)")
      ->check(integerIn(4, 16));
  sub->add_option("--bdam-triangles", o->bdamSettings.patchTriangles,
                  "--bdam: triangles each patch is simplified to (default 1024)")
      ->check(integerIn(16, 16384));
  return {
      sub,
      [o, maxError, quantum]() -> int {
        std::unique_ptr<tbb::global_control> limit;
        if (o->threads > 0) {
          limit = std::make_unique<tbb::global_control>(
              tbb::global_control::max_allowed_parallelism, std::size_t(o->threads));
        }
        BuildOptions options;
        options.tileSize = o->tileSize;
        options.codec = o->codec;
        if (maxError->count() > 0) options.maxErrorM = o->maxErrorM;
        if (quantum->count() > 0) options.quantumM = o->quantumM;
        options.zstdLevel = o->zstdLevel;
        // The builder converts the split threshold to steps once it knows the quantum.
        applyFractalRangeOptions(o->fractal, options.fractal, 1.0);
        options.dem.encoding = parseHeightEncoding(o->dem.encoding).value_or(HeightEncoding::Plain);
        if (o->dem.spacingM > 0.0) options.dem.spacingM = o->dem.spacingM;
        for (const std::string& input : o->dem.inputs) {
          if (looksLikeTileStore(input)) {
            return fail(
                makeError("'{}' is already a tile store (use tellus export to turn "
                          "a level back into a GeoTIFF)",
                          input));
          }
        }
        if (!o->global && o->blendEdgesM > 0.0) {
          return fail(makeError("--blend-edges applies to --global builds, where several "
                                "sources meet"));
        }
        if (!o->update.empty() && !o->global) {
          return fail(makeError("--update applies to --global stores"));
        }
        if (o->global) {
          if (o->bdam) return fail(makeError("--bdam builds patches for a flat store, not a --global one"));
          return runGlobalBuild(*o, maxError, quantum);
        }
        std::vector<std::filesystem::path> inputs(o->dem.inputs.begin(), o->dem.inputs.end());
        Result<BuildReport> report = BuildReport{};
        if (o->bdam) {
          if (const int code = buildStoreWithBdam(inputs, *o, options, report.value()); code != 0) return code;
        } else {
          report = buildPyramid(inputs, o->output, options);
          if (!report) return fail(report.error());
        }
        const StoreMetadata& m = report->metadata;
        fmt::print(
            "{}: {} levels, {} tiles of {}x{} samples, codec {}, {} ({:.2f}x smaller "
            "than int32 tiles), built in {:.1f} s\n",
            o->output, m.layout.levelCount(), report->tiles, m.layout.samplesPerSide(),
            m.layout.samplesPerSide(), m.codec, formatByteCount(double(report->fileBytes)),
            double(report->decodedBytes) / double(std::max<std::uint64_t>(1, report->payloadBytes)),
            report->seconds);
        return 0;
      },
      [o] {
        std::vector<std::string> outputs{o->output};
        if (o->bdam) outputs.push_back(bdam::defaultPatchFilePath(o->output).string());
        std::vector<std::string> inputs = o->dem.inputs;
        if (!o->update.empty()) inputs.push_back(o->update);
        return CommandFiles{inputs, outputs, {}};
      }};
}

}  // namespace tellus::cli
