// tellus generate: a deterministic procedural terrain written as a GeoTIFF in metres.
#include <spdlog/spdlog.h>

#include <chrono>
#include <cmath>
#include <filesystem>

#include <fmt/format.h>

#include "cli_numbers.hpp"
#include "cli_support.hpp"
#include "tellus/core/memory_budget.hpp"
#include "tellus/core/atomic_output.hpp"
#include "tellus/dem/geotiff_writer.hpp"
#include "tellus/dem/planet_generator.hpp"
#include "tellus/dem/srtm_tile_generator.hpp"
#include "tellus/core/number_fields.hpp"
#include "tellus/core/progress.hpp"
#include "tellus/dem/terrain_generator.hpp"

namespace tellus::cli {
namespace {

struct GenerateOptions {
  std::string output;
  TerrainParams params;
  bool planet = false;  // a whole planet in latitude/longitude instead (--size: columns)
  std::string srtmTiles;  // "W,S,E,N" or "land": SRTM-like tiles of the planet into -o DIR
  int detailOctaves = 10;
};

// `tellus generate --srtm-tiles W,S,E,N|land -o DIR`: the planet as SRTM3 tiles (issue 47's
// input data), every tile with land in the box (land: 60 S..60 N, as SRTM), into a new or empty
// folder. The work (tiles, bytes) is estimated and the disk checked before the first tile.
int writeSrtmTiles(const GenerateOptions& o) {
  LatLonDegreeBox box{-180, -60, 180, 60};
  if (o.srtmTiles != "land") {
    static constexpr const char* kFields[] = {"west", "south", "east", "north"};
    Result<std::vector<double>> v = parseNumberFields(o.srtmTiles, kFields, "--srtm-tiles box");
    if (!v) return fail(makeError("{} (or give 'land')", v.error().message));
    for (double d : *v) {
      if (d != std::floor(d)) return fail(makeError("--srtm-tiles: '{}' is not whole degrees", o.srtmTiles));
    }
    box = {int((*v)[0]), int((*v)[1]), int((*v)[2]), int((*v)[3])};
    if (box.west < -180 || box.east > 180 || box.south < -90 || box.north > 90 || box.west >= box.east ||
        box.south >= box.north) {
      return fail(makeError("--srtm-tiles {}: give west < east within -180..180 and south < north within "
                            "-90..90 (whole degrees)", o.srtmTiles));
    }
  }
  const std::filesystem::path folder(o.output);
  std::error_code ec;
  if (std::filesystem::exists(folder, ec)) {
    if (!std::filesystem::is_directory(folder, ec)) {
      return fail(makeError("'{}' exists and is not a folder: --srtm-tiles writes its tiles into a new or "
                            "empty folder", o.output));
    }
    if (!std::filesystem::is_empty(folder, ec)) {
      return fail(makeError("'{}' is not empty: --srtm-tiles writes only into a new or empty folder (it "
                            "never replaces files)", o.output));
    }
  }
  const PlanetField field({.columns = 2160, .seed = o.params.seed, .highestM = o.params.reliefM,
                           .plateau = std::nullopt});
  const auto start = std::chrono::steady_clock::now();
  std::vector<SrtmTileId> tiles;
  {
    Progress progress("finding land", 1);
    tiles = srtmLandTiles(field, box);
  }
  const std::uint64_t tileBytes = std::uint64_t(kSrtmTileSamples) * kSrtmTileSamples * 2;
  const std::uint64_t bytes = tileBytes * tiles.size();
  spdlog::info("{} tiles with land of {} in {}..{} E, {}..{} N: {} to write", tiles.size(),
               std::int64_t(box.east - box.west) * (box.north - box.south), box.west, box.east, box.south,
               box.north, formatByteCount(double(bytes)));
  if (tiles.empty()) return fail(makeError("--srtm-tiles {}: the planet (seed {}) has no land there", o.srtmTiles, o.params.seed));
  std::filesystem::create_directories(folder, ec);
  if (ec) return fail(makeError("cannot create '{}': {}", o.output, ec.message()));
  const std::filesystem::space_info space = std::filesystem::space(folder, ec);
  if (!ec && space.available < bytes + bytes / 20) {
    return fail(makeError("--srtm-tiles: {} tiles need {}, '{}' has {} free", tiles.size(),
                          formatByteCount(double(bytes)), o.output, formatByteCount(double(space.available))));
  }
  Progress progress("srtm tiles", tiles.size());
  for (const SrtmTileId& tile : tiles) {
    const std::vector<std::int16_t> samples = srtmTileSamples(field, tile, o.detailOctaves);
    if (Status written = writeSrtmTile(folder / srtmTileName(tile), samples); !written) return fail(written.error());
    progress.advance();
  }
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  spdlog::info("wrote {} SRTM-like tiles ({}) into {} in {:.1f} s (planet seed {})", tiles.size(),
               formatByteCount(double(bytes)), o.output, seconds, o.params.seed);
  return 0;
}

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
  sub->add_option("-o,--output", options->output,
                  "Output GeoTIFF file (with --srtm-tiles: the folder of tiles, new or empty)")
      ->required();
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
  sub->add_option("--srtm-tiles", options->srtmTiles,
                  "The planet as SRTM3 tiles instead (1201 x 1201 Int16 .hgt, named as SRTM, voids, "
                  "sea tiles left out) of the box W,S,E,N (whole degrees), or 'land' (60 S..60 N), "
                  "into the folder -o; --seed and --relief as for --planet")
      ->excludes("--planet");
  sub->add_option("--srtm-detail", options->detailOctaves,
                  "--srtm-tiles: octaves of relief below the planet's own, from 50 km down (default 10: "
                  "about 50 m)")
      ->check(integerIn(0, 16));
  return {sub, [options]() -> int {
            if (!options->srtmTiles.empty()) return writeSrtmTiles(*options);
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
          [options] {
            if (!options->srtmTiles.empty()) return CommandFiles{{}, {}, {options->output}};
            return CommandFiles{{}, {options->output}, {}};
          }};
}

}  // namespace tellus::cli
