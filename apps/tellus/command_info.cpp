// tellus info: what a DEM is (size, CRS, spacing, heights, voids) and what the GL context offers.
#include <fmt/format.h>

#include "cli_support.hpp"
#include "global_store_cli.hpp"
#include "stack_cli.hpp"
#include "tellus/core/memory_budget.hpp"
#include "tellus/dem/dem_source.hpp"
#include "tellus/gl/gl_info.hpp"

namespace tellus::cli {
namespace {

struct InfoOptions {
  DemInputOptions dem;
  bool gl = false;
  std::string context = "headless";
};

// Describes DEM inputs from their metadata and one streaming pass over their heights, in
// constant memory (a 100000 x 100000 raster is described without loading it).
int printDemInfo(const DemInputOptions& options) {
  if (Status s = checkNoTileStoreInMosaic(options.inputs); !s) return fail(s.error());
  DemLoadOptions load;
  load.encoding = parseHeightEncoding(options.encoding).value_or(HeightEncoding::Plain);
  if (options.spacingM > 0.0) load.spacingM = options.spacingM;
  const std::vector<std::filesystem::path> paths(options.inputs.begin(), options.inputs.end());
  Result<std::unique_ptr<DemSource>> source = DemSource::open(paths, load);
  if (!source) return fail(source.error());
  Result<DemStatistics> stats = source.value()->scanStatistics();
  if (!stats) return fail(stats.error());
  const DemSourceInfo& info = source.value()->info();
  const auto row = [](std::string_view name, const std::string& value) {
    fmt::print("{:<18}{}\n", fmt::format("{}:", name), value);
  };
  row("input", options.inputs.size() == 1
                   ? options.inputs[0]
                   : fmt::format("{} files (mosaic)", options.inputs.size()));
  row("size", fmt::format("{} x {} samples", info.width, info.height));
  std::string crs = info.georef.crsName.empty() ? "none" : info.georef.crsName;
  if (!info.georef.crsName.empty())
    crs += info.georef.isGeographic ? " (geographic)" : " (projected)";
  row("CRS", crs);
  if (info.georef.hasGeoTransform) {
    const auto& gt = info.georef.geoTransform;
    row("geotransform",
        fmt::format("origin ({:.6f}, {:.6f}), pixel {:.9g} x {:.9g}", gt[0], gt[3], gt[1], gt[5]));
  }
  row("sample spacing",
      fmt::format("{:.3f} m (east-west) x {:.3f} m (north-south)", info.spacingXM, info.spacingYM));
  row("extent", fmt::format("{:.2f} km x {:.2f} km", (info.width - 1) * info.spacingXM / 1000.0,
                            (info.height - 1) * info.spacingYM / 1000.0));
  const DemStatistics& s = stats.value();
  const std::string sampled =
      s.rowStep > 1 ? fmt::format(" (estimated from 1 row in {}: the raster is too large to "
                                  "read whole for a description)",
                                  s.rowStep)
                    : std::string();
  row("heights", s.hasValidSamples
                     ? fmt::format("min {:.2f} m, max {:.2f} m{}", s.minM, s.maxM, sampled)
                     : "none: every sample is void");
  if (s.rowStep > 1) {
    row("voids", s.voids == 0 ? std::string("none seen")
                              : fmt::format("{} among the {} samples read (filled by "
                                            "interpolation when loaded)",
                                            s.voids, s.samplesRead));
  } else {
    row("voids", s.voids == 0
                     ? std::string("none")
                     : fmt::format("{} (filled by interpolation when loaded)", s.voids));
  }
  return 0;
}

}  // namespace

int printStoreInfo(const DemInputOptions& input) {
  const std::string& path = input.inputs.at(0);
  Result<std::shared_ptr<TileStore>> opened = openTileStore(input);
  if (!opened) return fail(opened.error());
  const TileStore& store = *opened.value();
  const StoreMetadata& m = store.metadata();
  const PyramidLayout& layout = m.layout;
  const auto row = [](std::string_view name, const std::string& value) {
    fmt::print("{:<18}{}\n", fmt::format("{}:", name), value);
  };
  row("store", fmt::format("{} ({})", path, m.producer));
  row("data", fmt::format("{} x {} samples", layout.dataWidth(), layout.dataHeight()));
  row("tiles", fmt::format("{} cells ({} x {} samples), {} tiles in {} levels", layout.tileSize(),
                           layout.samplesPerSide(), layout.samplesPerSide(), layout.tileCount(),
                           layout.levelCount()));
  std::string crs = m.georef.crsName.empty() ? "none" : m.georef.crsName;
  if (!m.georef.crsName.empty()) crs += m.georef.isGeographic ? " (geographic)" : " (projected)";
  row("CRS", crs);
  row("sample spacing", fmt::format("{:.3f} m (east-west) x {:.3f} m (north-south) at level 0",
                                    m.spacingXM, m.spacingYM));
  row("heights", fmt::format("min {:.2f} m, max {:.2f} m (metres, quantum {} m)", m.minHeightM,
                             m.maxHeightM, m.quantumM));
  std::string codec = fmt::format("{} (max error {} m)", m.codec, m.maxErrorM);
  if (m.maxErrorMeasured) {
    codec = fmt::format("{} (no bound; the largest error the build measured is {} m)", m.codec,
                        m.maxErrorM);
  } else if (m.maxErrorSteps == 0) {
    codec = m.maxErrorM == 0.0 ? fmt::format("{} (lossless)", m.codec)
                               : fmt::format(
                                     "{} (lossless at the quantum; rounding the input to "
                                     "it moved heights by at most {} m)",
                                     m.codec, m.maxErrorM);
  }
  row("codec", codec);
  row("voids", m.filledVoidCount == 0
                   ? std::string("none")
                   : fmt::format("{} (filled by interpolation)", m.filledVoidCount));
  const std::uint64_t decodedPerTile = layout.tileShape().sampleCount() * 4;
  std::uint64_t payload = 0;
  for (const TileRecord& r : store.records()) payload += r.payloadBytes;
  row("size", fmt::format("{} file, {} of tiles: {:.2f} bits/sample, {:.2f}x smaller than int32",
                          formatByteCount(double(store.fileBytes())), formatByteCount(double(payload)),
                          8.0 * double(payload) /
                              double(layout.tileCount() * layout.tileShape().sampleCount()),
                          double(decodedPerTile * layout.tileCount()) /
                              double(std::max<std::uint64_t>(payload, 1))));
  fmt::print("\n{:>5} {:>11} {:>7} {:>12} {:>14} {:>14}\n", "level", "tiles", "spacing", "bytes",
             "bytes/tile", "max error m");
  for (int level = 0; level < layout.levelCount(); ++level) {
    std::uint64_t bytes = 0;
    float worst = 0.0f;
    std::size_t count = 0;
    for (const TileRecord& r : store.records()) {
      if (r.key.level != level) continue;
      bytes += r.payloadBytes;
      worst = std::max(worst, r.stats.geometricErrorM);
      ++count;
    }
    fmt::print("{:>5} {:>11} {:>6.1f}m {:>12} {:>14.0f} {:>14.2f}\n", level,
               fmt::format("{}x{}", layout.tilesX(level), layout.tilesY(level)),
               m.spacingXM * PyramidLayout::stride(level), formatByteCount(double(bytes)),
               double(bytes) / double(count), worst);
  }
  return 0;
}

Command addInfoCommand(CLI::App& app) {
  auto options = std::make_shared<InfoOptions>();
  CLI::App* sub =
      app.add_subcommand("info", "Describe DEM files, a tile store and/or the OpenGL context");
  addDemInputOptions(sub, options->dem, false, InputKinds::AnyTerrain);
  sub->add_flag("--gl", options->gl, "Print the OpenGL vendor, renderer, version and limits");
  sub->add_option("--context", options->context, "OpenGL context: headless (EGL) or window (GLFW)")
      ->check(CLI::IsMember({"headless", "window"}));
  return {sub, [options, sub]() -> int {
            if (options->dem.inputs.empty() && !options->gl) {
              return fail(makeError("info: give DEM files and/or --gl (see tellus info --help)"));
            }
            // The input is read once (classified()); the store opens from what was read.
            const TerrainInputKind kind = options->dem.classified().kind;
            if (kind == TerrainInputKind::Stacks) {
              if (int code = printStackInfo(options->dem.inputs[0]); code != 0) return code;
            } else if (kind == TerrainInputKind::GlobalStore) {
              if (int code = printGlobalStoreInfo(options->dem); code != 0) return code;
            } else if (kind == TerrainInputKind::TileStore) {
              if (int code = printStoreInfo(options->dem); code != 0) return code;
            } else if (!options->dem.inputs.empty()) {
              if (int code = printDemInfo(options->dem); code != 0) return code;
            }
            if (options->gl) {
              Result<std::unique_ptr<gl::GlContext>> context = createContext(options->context);
              if (!context) return fail(context.error());
              if (!options->dem.inputs.empty()) fmt::print("\n");
              fmt::print("{}", gl::formatGlInfo(gl::queryGlInfo(), context.value()->description()));
            }
            (void)sub;
            return 0;
          },
          [options] { return CommandFiles{options->dem.inputs, {}, {}}; }};
}

}  // namespace tellus::cli
