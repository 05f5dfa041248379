// tellus generate: a deterministic procedural terrain written as a GeoTIFF in metres.
#include <spdlog/spdlog.h>

#include <cmath>

#include <fmt/format.h>

#include "cli_numbers.hpp"
#include "cli_support.hpp"
#include "tellus/core/memory_budget.hpp"
#include "tellus/core/atomic_output.hpp"
#include "tellus/dem/geotiff_writer.hpp"
#include "tellus/dem/planet_generator.hpp"
#include "tellus/dem/terrain_generator.hpp"

namespace tellus::cli {
namespace {

struct GenerateOptions {
  std::string output;
  TerrainParams params;
  bool planet = false;  // a whole planet in latitude/longitude instead (--size: columns)
};

// `tellus generate --planet`: the planet generator's grid, --size samples around the equator.
int writePlanet(const GenerateOptions& options) {
  if (options.params.size < kMinPlanetColumns || options.params.size > kMaxPlanetColumns) {
    return fail(makeError("--planet: --size is the samples around the equator, {} to {}; got {}",
                          kMinPlanetColumns, kMaxPlanetColumns, options.params.size));
  }
  const double samples = double(options.params.size) * double(options.params.size) / 2.0;
  if (Status s = checkMemoryFor("generating the planet", samples * 8.0, "use a smaller --size");
      !s) {
    return fail(s.error());
  }
  const HeightGrid grid = generatePlanet({.columns = options.params.size,
                                          .seed = options.params.seed,
                                          .highestM = options.params.reliefM,
                                          .plateau = std::nullopt});
  if (Status written = writeGeoTiff(grid, options.output); !written) return fail(written.error());
  const HeightRange range = grid.heightRange();
  spdlog::info("wrote {} (a planet: {} x {} samples of {:.4f} degrees, heights {:.0f}..{:.0f} m)",
               options.output, grid.width, grid.height, 360.0 / grid.width, range.minM,
               range.maxM);
  return 0;
}

// The generated grid is placed in UTM zone 33N (EPSG:32633), north-west corner at
// 400 000 E, 5 200 000 N, so GIS tools show it in metres at a plausible place.
constexpr int kEpsg = 32633;
constexpr double kWestEasting = 400000.0, kNorthNorthing = 5200000.0;

}  // namespace

Result<HeightGrid> generateGeoreferencedTerrain(const TerrainParams& params) {
  if (Status valid = checkTerrainParams(params); !valid) return valid.error();
  const double samples = double(params.size) * double(params.size);
  // The largest size that fits, for the message.
  const int fits = int(std::sqrt(double(availableMemoryBytes()) / kTerrainBytesPerSample));
  if (Status s = checkMemoryFor(fmt::format("generating a {0} x {0} terrain", params.size),
                                samples * kTerrainBytesPerSample,
                                fmt::format("use a smaller --size (about {} fits)", fits));
      !s) {
    return s.error();
  }
  HeightGrid grid = generateTerrain(params);
  Result<GeoReference> georef =
      projectedGeoReference(kEpsg, kWestEasting, kNorthNorthing, params.spacingM);
  if (!georef) return georef.error();
  grid.georef = georef.value();
  return grid;
}

Command addGenerateCommand(CLI::App& app) {
  auto options = std::make_shared<GenerateOptions>();
  CLI::App* sub =
      app.add_subcommand("generate", "Write a procedural mountain terrain as a GeoTIFF");
  sub->add_option("-o,--output", options->output, "Output GeoTIFF file")->required();
  sub->add_option("--size", options->params.size, "Samples per side (the grid is size x size)")
      ->check(integerIn(kMinTerrainSize, kMaxTerrainSize))
      ->capture_default_str();
  addSeedOption(sub, options->params.seed);
  sub->add_option("--spacing", options->params.spacingM, "Metres between samples")
      ->check(numberIn(kMinTerrainSpacingM, kMaxTerrainSpacingM))
      ->capture_default_str();
  sub->add_option("--relief", options->params.reliefM, "Height of the highest ridges, metres")
      ->check(numberIn(kMinReliefM, kMaxReliefM))
      ->capture_default_str();
  sub->add_option("--erosion", options->params.erosion, "Erosion strength (0 = none)")
      ->check(numberIn(0.0, kMaxErosion))
      ->capture_default_str();
  sub->add_flag("--planet", options->planet,
                "A whole planet instead: a WGS 84 latitude/longitude grid of --size samples "
                "around the equator (and half as many from pole to pole), oceans and "
                "continents, --relief the highest peaks (a global source for build --global)");
  return {sub, [options]() -> int {
            if (Status writable = checkOutputWritable(options->output); !writable) {
              return fail(writable.error());
            }
            if (options->planet) return writePlanet(*options);
            Result<HeightGrid> grid = generateGeoreferencedTerrain(options->params);
            if (!grid) return fail(grid.error());
            if (Status written = writeGeoTiff(grid.value(), options->output); !written) {
              return fail(written.error());
            }
            const HeightRange range = grid->heightRange();
            spdlog::info("wrote {} ({} x {} samples, {} m spacing, heights {:.0f}..{:.0f} m)",
                         options->output, grid->width, grid->height, options->params.spacingM,
                         range.minM, range.maxM);
            return 0;
          },
          [options] { return CommandFiles{{}, {options->output}, {}}; }};
}

}  // namespace tellus::cli
