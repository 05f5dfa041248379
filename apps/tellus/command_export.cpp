// tellus export: terrain out of a store for other tools: one level as a GeoTIFF (-o), a region
// as an adaptive glTF mesh (--gltf), or a Cesium quantized-mesh tile set (--quantized-mesh).
#include <cctype>
#include <chrono>
#include <mutex>

#include <fmt/format.h>

#include "cli_numbers.hpp"
#include "cli_support.hpp"
#include "global_store_cli.hpp"
#include "tellus/core/atomic_output.hpp"
#include "tellus/core/progress.hpp"
#include "tellus/dem/geoid.hpp"
#include "tellus/core/stopwatch.hpp"
#include "tellus/dem/dem_loader.hpp"
#include "tellus/dem/water_mask.hpp"
#include "tellus/export/lonlat_sampler.hpp"
#include "tellus/export/tiles3d_export.hpp"
#include "tellus/dem/geotiff_writer.hpp"
#include "tellus/export/gltf_export.hpp"
#include "tellus/export/quantized_mesh_tiler.hpp"

namespace tellus::cli {
namespace {
struct ExportOptions {
  std::string store;
  std::string output;  // GeoTIFF
  std::string gltf;
  std::string quantizedMesh;
  std::string tiles3d;
  int level = 0;
  int depth = -1;
  std::string region;
  double maxErrorM = 1.0;
  std::string colours = "none";
  std::uint64_t maxSamples = std::uint64_t(4) << 20;
  int maxLevel = -1;
  int tileSamples = 65;
  int globeLevels = 5;
  std::string geoid;
  std::string water;
  int metadataLevels = 0;
  bool quantize = false;
  std::string texture;
  int textureSize = 2048;
  std::string background;
};

int exportGltfMesh(const ExportOptions& o) {
  Result<std::shared_ptr<TileStore>> store = openTileStore(o.store);
  if (!store) return fail(store.error());
  GltfExportOptions options;
  options.maxErrorM = o.maxErrorM;
  options.maxSamples = o.maxSamples;
  options.hypsometricColours = o.colours == "hypsometric";
  options.quantize = o.quantize;
  options.texture = o.texture;
  options.textureMaxSide = o.textureSize;
  if (!o.region.empty()) {
    Result<GeoBounds> region = parseGeoBounds(o.region);
    if (!region) return fail(region.error());
    options.region = LonLatBox{region->westDeg, region->southDeg, region->eastDeg, region->northDeg};
  }
  const Stopwatch elapsed;
  Result<GltfExportReport> report = exportGltf(*store.value(), o.gltf, options);
  if (!report) return fail(report.error());
  const double seconds = elapsed.elapsedS();
  fmt::print("{}: level {} of {}, {} x {} samples -> {} vertices, {} triangles, max 3-D error "
             "{:.3f} m against level {}'s samples (bound {} m), {:.2f} MiB, {:.1f} s\n",
             o.gltf, report->storeLevel, o.store, report->width, report->height,
             report->vertices, report->triangles, report->maxErrorM, report->storeLevel, o.maxErrorM,
             double(report->bytes) / (1 << 20), seconds);
  if (report->storeLevel > 0) {
    fmt::print("level {} has 1 sample in {} of each row and column of level 0: give a larger "
               "--max-samples or a smaller --region for the finest data\n",
               report->storeLevel, 1 << report->storeLevel);
  }
  if (report->textureWidth > 0) {
    fmt::print("texture: {} warped to {} x {} pixels over the mesh ({:.1f} % covered by it, the rest grey)\n",
               o.texture, report->textureWidth, report->textureHeight, 100.0 * report->textureCoverage);
  }
  fmt::print("frame: east-north-up at {:.6f}, {:.6f} (x east, y up, z south, metres; the node's "
             "extras hold the matrix to ECEF)\n",
             report->originLonDeg, report->originLatDeg);
  return 0;
}

// The per-level table of a tile set: tiles, triangles, MiB, points measured, the level's
// geometric error and the largest 3-D error measured.
void printPyramidLevels(const std::vector<PyramidLevelReport>& levels) {
  // Points measured: the source samples inside each tile (one per quantized position; every
  // k-th column and row in tiles of more than 4 million), and lattice points without data.
  fmt::print("level  tiles  triangles  MiB  points measured  bound m  max 3-D error m\n");
  for (const PyramidLevelReport& l : levels) {
    const std::string measured = l.truthStride == 1
                                     ? fmt::format("{}", l.truthSamples)
                                     : fmt::format("{} (1 in {}^2)", l.truthSamples, l.truthStride);
    fmt::print("{:5}  {:5}  {:9}  {:.2f}  {:>15}  {:.2f}  {:.2f}\n", l.level, l.tiles, l.triangles,
               double(l.bytes) / (1 << 20), measured, l.geometricErrorM, l.maxErrorM);
  }
}

void printHeightsNote(const ExportOptions& o) {
  if (!o.geoid.empty()) {
    fmt::print("heights: above the WGS84 ellipsoid (store heights + the geoid's undulation)\n");
  } else {
    fmt::print("heights: the store's, written as ellipsoidal (give --geoid for SRTM's EGM96 heights)\n");
  }
}

// A progress bar made on the first tile (when the count is known), advanced from any thread.
struct TileProgress {
  std::unique_ptr<Progress> bar;
  std::once_flag made;
  std::function<void(std::uint64_t, std::uint64_t)> callback(const char* what) {
    return [this, what](std::uint64_t, std::uint64_t total) {
      std::call_once(made, [&] { bar = std::make_unique<Progress>(what, total); });
      bar->advance();
    };
  }
};

Result<std::optional<Geoid>> loadGeoidOption(const ExportOptions& o) {
  if (o.geoid.empty()) return std::optional<Geoid>();
  Result<Geoid> loaded = Geoid::load(o.geoid);
  if (!loaded) return loaded.error();
  return std::optional<Geoid>(std::move(loaded.value()));
}

// The ground beyond the data (--background): any DEM GDAL reads, as a latitude/longitude
// sampler (a global grid wraps at the antimeridian).
Result<std::optional<LonLatSampler>> loadBackgroundOption(const ExportOptions& o) {
  if (o.background.empty()) return std::optional<LonLatSampler>();
  Result<HeightGrid> grid = loadDem({o.background});
  if (!grid) return grid.error();
  Result<LonLatSampler> sampler = LonLatSampler::create(std::move(grid.value()));
  if (!sampler) return makeError("'{}': {}", o.background, sampler.error().message);
  return std::optional<LonLatSampler>(std::move(sampler.value()));
}

// What a tile set export reads: the store, and the geoid and background when given.
struct TileSetInputs {
  std::shared_ptr<TileStore> store;
  std::optional<Geoid> geoid;
  std::optional<LonLatSampler> background;
  const Geoid* geoidOrNull() const { return geoid ? &*geoid : nullptr; }
  const LonLatSampler* backgroundOrNull() const { return background ? &*background : nullptr; }
};

Result<TileSetInputs> loadTileSetInputs(const ExportOptions& o) {
  TileSetInputs inputs;
  Result<std::shared_ptr<TileStore>> store = openTileStore(o.store);
  if (!store) return store.error();
  inputs.store = std::move(store.value());
  Result<std::optional<Geoid>> geoid = loadGeoidOption(o);
  if (!geoid) return geoid.error();
  inputs.geoid = std::move(geoid.value());
  Result<std::optional<LonLatSampler>> background = loadBackgroundOption(o);
  if (!background) return background.error();
  inputs.background = std::move(background.value());
  return inputs;
}

int exportTiles3dSet(const ExportOptions& o) {
  Result<TileSetInputs> inputs = loadTileSetInputs(o);
  if (!inputs) return fail(inputs.error());
  Tiles3dExportOptions options;
  options.pyramid = {o.maxLevel, o.tileSamples, o.globeLevels};
  options.geoid = inputs->geoidOrNull();
  options.background = inputs->backgroundOrNull();
  options.quantize = o.quantize;
  TileProgress progress;
  options.progress = progress.callback("3D Tiles tiles");
  const Stopwatch elapsed;
  Result<Tiles3dExportReport> report = exportTiles3d(*inputs->store, o.tiles3d, options);
  progress.bar.reset();
  if (!report) return fail(report.error());
  const double seconds = elapsed.elapsedS();
  fmt::print("{}: 3D Tiles 1.1 set of {}, implicit quadtrees of levels 0..{}, {} glTF tiles, {:.2f} MiB, "
             "{} subtrees of {} levels, {:.1f} s\n",
             o.tiles3d, o.store, int(report->levels.size()) - 1, report->tiles,
             double(report->bytes) / (1 << 20), report->subtrees, report->subtreeLevels, seconds);
  printPyramidLevels(report->levels);
  printHeightsNote(o);
  return 0;
}

int exportQuantizedMeshTiles(const ExportOptions& o) {
  Result<TileSetInputs> inputs = loadTileSetInputs(o);
  if (!inputs) return fail(inputs.error());
  QuantizedMeshExportOptions options;
  options.background = inputs->backgroundOrNull();
  options.maxLevel = o.maxLevel;
  options.tileSamples = o.tileSamples;
  options.globeLevels = o.globeLevels;
  options.geoid = inputs->geoidOrNull();
  std::optional<WaterMask> water;
  if (!o.water.empty()) {
    Result<WaterMask> loaded = WaterMask::load(o.water);
    if (!loaded) return fail(loaded.error());
    water = std::move(loaded.value());
  }
  options.waterMask = water ? &*water : nullptr;
  options.metadataLevels = o.metadataLevels;
  TileProgress progress;
  options.progress = progress.callback("quantized-mesh tiles");
  const Stopwatch elapsed;
  Result<QuantizedMeshExportReport> report = exportQuantizedMesh(*inputs->store, o.quantizedMesh, options);
  progress.bar.reset();
  if (!report) return fail(report.error());
  const double seconds = elapsed.elapsedS();
  fmt::print("{}: quantized-mesh-1.0 tile set of {}, levels 0..{}, {} tiles, {:.2f} MiB, {:.1f} s\n",
             o.quantizedMesh, o.store, int(report->levels.size()) - 1, report->tiles,
             double(report->bytes) / (1 << 20), seconds);
  printPyramidLevels(report->levels);
  printHeightsNote(o);
  return 0;
}

// A global store: one depth over a region (default the whole globe at the deepest depth that
// fits the sample budget).
int exportGlobal(const ExportOptions& o) {
  Result<std::shared_ptr<GlobalStore>> store = GlobalStore::open(o.store);
  if (!store) return fail(store.error());
  GlobalRegionRequest request;
  if (o.depth >= 0) request.depth = o.depth;
  if (!o.region.empty()) {
    Result<GeoBounds> region = parseGeoBounds(o.region);
    if (!region) return fail(region.error());
    request.region = region.value();
  }
  Result<GlobalRegion> chosen = chooseGlobalRegion(*store.value(), request);
  if (!chosen) return fail(chosen.error());
  Result<HeightGrid> grid = loadGlobalStoreRegion(*store.value(), request);
  if (!grid) return fail(grid.error());
  if (Status s = writeGeoTiff(grid.value(), o.output); !s) return fail(s.error());
  fmt::print("{}: depth {} of {}, {} x {} samples\n", o.output, chosen->depth, o.store,
             grid->width, grid->height);
  return 0;
}
}  // namespace

Command addExportCommand(CLI::App& app) {
  auto o = std::make_shared<ExportOptions>();
  CLI::App* sub = app.add_subcommand(
      "export", "Write a store as a GeoTIFF (-o), a glTF mesh (--gltf), Cesium terrain tiles "
                "(--quantized-mesh) or a 3D Tiles set (--3d-tiles)");
  sub->add_option("store", o->store, "The tile store (.tstore, a file or an http(s):// URL)")->required();
  sub->add_option("-o,--output", o->output, "The GeoTIFF to write (one level)");
  sub->add_option("--gltf", o->gltf,
                  "A binary glTF (.glb) to write: an adaptive mesh of --region within --max-error");
  sub->add_option("--quantized-mesh", o->quantizedMesh,
                  "A folder to write a Cesium quantized-mesh-1.0 tile set into (layer.json, "
                  "Z/X/Y.terrain)");
  sub->add_option("--3d-tiles", o->tiles3d,
                  "A folder to write a 3D Tiles 1.1 tile set into (tileset.json, implicit quadtrees of "
                  "glTF tiles: the quantized-mesh tiles' meshes, within the same errors)");
  sub->add_option("--max-error", o->maxErrorM,
                  "glTF: the largest vertical error of the mesh, metres (default 1)")
      ->check(numberIn(0.0, 1e6));
  sub->add_option("--colours", o->colours, "glTF: vertex colours, none or hypsometric")
      ->check(CLI::IsMember({"none", "hypsometric"}));
  sub->add_flag("--quantize", o->quantize,
                "glTF and 3D Tiles: store positions, normals and texture coordinates as KHR_mesh_quantization "
                "integers (about half the bytes; positions within 1/65535 of the mesh's size)");
  sub->add_option("--texture", o->texture,
                  "glTF: drape a georeferenced RGB image (any CRS: a Landsat GeoTIFF, Blue Marble with its "
                  "world file) as the mesh's base colour, embedded as a JPEG");
  sub->add_option("--texture-size", o->textureSize, "glTF: the texture's longest side, pixels (default 2048)")
      ->check(integerIn(16, 16384));
  sub->add_option("--max-samples", o->maxSamples,
                  "glTF: the most store samples the region may read (a coarser level beyond; "
                  "default 4194304)")
      ->check(integerIn(4, std::int64_t(1) << 32));
  sub->add_option("--max-level", o->maxLevel,
                  "Quantized mesh and 3D Tiles: the finest level (default: as fine as the store's samples)")
      ->check(integerIn(0, 20));
  sub->add_option("--tile-samples", o->tileSamples,
                  "Quantized mesh and 3D Tiles: lattice samples per tile side (default 65): the finest level is the first "
                  "whose lattice is as fine as the store's samples; where there is no data the lattice "
                  "(at least 65) stands for the ground")
      ->check(integerIn(3, 1025));
  sub->add_option("--globe-levels", o->globeLevels,
                  "Quantized mesh and 3D Tiles: levels 0..N cover the whole globe (the geoid where there is no data), "
                  "so that Cesium draws the planet round from every distance; deeper levels cover the data "
                  "(default 5: 2,730 tiles)")
      ->check(integerIn(0, 8));
  sub->add_option("--geoid", o->geoid,
                  "Quantized mesh and 3D Tiles: a geoid grid (EGM96) to make the store's heights ellipsoidal");
  sub->add_option("--background", o->background,
                  "Quantized mesh and 3D Tiles: the ground beyond the store's data, a coarser DEM (ETOPO5, "
                  "heights above the geoid; sea floors drawn as the sea surface), so that the data's edge "
                  "meets it instead of falling to the geoid");
  sub->add_option("--water", o->water,
                  "Quantized mesh: a water mask (an 8-bit latitude/longitude raster, 0 land .. 255 water, "
                  "as BlueMarbleWater.jpg) for the watermask extension");
  sub->add_option("--metadata-levels", o->metadataLevels,
                  "Quantized mesh: the metadata extension; tiles of levels 0, N, 2N... list the available "
                  "tiles of the N levels under them, and layer.json says metadataAvailability N (as Cesium "
                  "World Terrain, N = 10); default 0: none, layer.json lists every level")
      ->check(integerIn(0, 20));
  sub->add_option("--level", o->level, "Pyramid level (0 = full resolution)")
      ->check(integerIn(0, kMaxStoreLevel));
  sub->add_option("--depth", o->depth,
                  "Global stores: the depth to export (default: the deepest that fits)")
      ->check(integerIn(0, GlobalTiling::kMaxDepth));
  sub->add_option("--region", o->region,
                  "Global stores and glTF: WEST,SOUTH,EAST,NORTH degrees (default: everything)");
  return {sub,
          [o]() -> int {
            const int outputs = int(!o->output.empty()) + int(!o->gltf.empty()) +
                                int(!o->quantizedMesh.empty()) + int(!o->tiles3d.empty());
            if (outputs != 1) {
              return fail(makeError("give one output: -o FILE.tif, --gltf FILE.glb, "
                                    "--quantized-mesh FOLDER or --3d-tiles FOLDER"));
            }
            // What each output holds is what its name says: a GeoTIFF, a binary glTF.
            const auto endsWith = [](const std::string& name, std::initializer_list<const char*> suffixes) {
              std::string lower = std::filesystem::path(name).extension().string();
              for (char& c : lower) c = char(std::tolower(static_cast<unsigned char>(c)));
              for (const char* suffix : suffixes) {
                if (lower == suffix) return true;
              }
              return false;
            };
            if (!o->output.empty() && !endsWith(o->output, {".tif", ".tiff"})) {
              return fail(makeError("'{}': -o writes a GeoTIFF; give a name ending in .tif or .tiff",
                                    o->output));
            }
            if (!o->gltf.empty() && !endsWith(o->gltf, {".glb"})) {
              return fail(makeError("'{}': --gltf writes a binary glTF; give a name ending in .glb",
                                    o->gltf));
            }
            if (o->quantizedMesh.empty() && (!o->water.empty() || o->metadataLevels != 0)) {
              return fail(makeError("--water and --metadata-levels apply to --quantized-mesh"));
            }
            if (o->gltf.empty() && !o->texture.empty()) {
              return fail(makeError("--texture applies to --gltf"));
            }
            if (o->gltf.empty() && o->tiles3d.empty() && o->quantize) {
              return fail(makeError("--quantize applies to --gltf and --3d-tiles"));
            }
            if (o->quantizedMesh.empty() && o->tiles3d.empty() && (!o->geoid.empty() || !o->background.empty())) {
              return fail(makeError("--geoid and --background apply to --quantized-mesh and --3d-tiles"));
            }
            if (!o->gltf.empty() || !o->quantizedMesh.empty() || !o->tiles3d.empty()) {
              if (!isTileStoreInput({o->store}) || isGlobalStore(o->store)) {
                return fail(makeError("'{}' is not a flat tile store (make one with tellus build)",
                                      o->store));
              }
              if ((!o->quantizedMesh.empty() || !o->tiles3d.empty()) && !o->region.empty()) {
                return fail(makeError("--region applies to --gltf and to -o of a global store; a "
                                      "tile set covers the whole store"));
              }
              if (!o->tiles3d.empty()) return exportTiles3dSet(*o);
              return o->gltf.empty() ? exportQuantizedMeshTiles(*o) : exportGltfMesh(*o);
            }
            if (isTileStoreInput({o->store}) && isGlobalStore(o->store)) return exportGlobal(*o);
            if (o->depth >= 0 || !o->region.empty()) {
              return fail(makeError("--depth and --region apply to --gltf and to -o of a global "
                                    "store; -o of a flat store writes one whole level (--level)"));
            }
            DemInputOptions input;
            input.inputs = {o->store};
            input.storeLevel = o->level;
            if (!isTileStoreInput(input.inputs)) {
              return fail(makeError("'{}' is not a tile store (make one with tellus build)",
                                    o->store));
            }
            Result<HeightGrid> grid = loadDemInputs(input);  // checks the memory it needs
            if (!grid) return fail(grid.error());
            if (Status s = writeGeoTiff(grid.value(), o->output); !s) return fail(s.error());
            fmt::print("{}: level {} of {}, {} x {} samples\n", o->output, o->level, o->store,
                       grid->width, grid->height);
            return 0;
          },
          [o] {
            std::vector<std::string> inputs{o->store};
            if (!o->geoid.empty()) inputs.push_back(o->geoid);
            if (!o->water.empty()) inputs.push_back(o->water);
            if (!o->texture.empty()) inputs.push_back(o->texture);
            if (!o->background.empty()) inputs.push_back(o->background);
            std::vector<std::string> outputs;
            for (const std::string* out : {&o->output, &o->gltf}) {
              if (!out->empty()) outputs.push_back(*out);
            }
            return CommandFiles{inputs, outputs, {}};
          }};
}

}  // namespace tellus::cli
