#include "support/terrain_fixtures.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

#include "support/test_support.hpp"

#include "tellus/dem/geotiff_writer.hpp"
#include "tellus/render/registry/renderer_registry.hpp"
#include "tellus/tiles/global_store.hpp"
#include "tellus/tiles/global_store_builder.hpp"
#include "tellus/tiles/pyramid_builder.hpp"
#include "tellus/render/output/offscreen_target.hpp"

namespace tellus::test {

HeightGrid writeGeneratedTerrain(const TerrainParams& params,
                                 const std::filesystem::path& geotiff) {
  HeightGrid grid = generateTerrain(params);
  grid.georef = projectedGeoReference(32652, 300000.0, 4200000.0, params.spacingM).value();
  std::filesystem::create_directories(geotiff.parent_path());
  const Status written = writeGeoTiff(grid, geotiff);
  EXPECT_TRUE(written) << (written ? "" : written.error().message);
  return grid;
}

GeneratedStore buildGeneratedStore(const TerrainParams& params, const std::filesystem::path& dir,
                                   int tileSize) {
  writeGeneratedTerrain(params, dir / "terrain.tif");
  BuildOptions build;
  build.tileSize = tileSize;
  const Result<BuildReport> built = buildPyramid({dir / "terrain.tif"}, dir / "terrain.tstore", build);
  EXPECT_TRUE(built) << (built ? "" : built.error().message);
  if (!built) return {};
  Result<std::shared_ptr<TileStore>> store = TileStore::open(dir / "terrain.tstore");
  EXPECT_TRUE(store) << (store ? "" : store.error().message);
  if (!store) return {};
  Result<HeightGrid> level0 = readStoreLevel(*store.value(), 0);
  EXPECT_TRUE(level0) << (level0 ? "" : level0.error().message);
  if (!level0) return {};
  return {store.value(), std::move(level0.value())};
}

PathRunOptions qualityRun(int width, int height, int warmupFrames) {
  PathRunOptions options;
  options.width = width;
  options.height = height;
  options.warmupFrames = warmupFrames;
  options.quality = true;
  return options;
}

CoverageMasks referenceCoverage(const HeightGrid& grid, const std::vector<Camera>& cameras,
                                const PathRunOptions& options) {
  RendererInputs inputs;
  inputs.grid = &grid;
  Result<std::unique_ptr<TerrainRenderer>> reference = makeRenderer("reference", inputs);
  EXPECT_TRUE(reference);
  if (!reference) return {};
  PathRunOptions coverageOnly = options;
  coverageOnly.keepFrames.clear();
  Result<PathRun> run = runPath(*reference.value(), cameras, grid, coverageOnly);
  EXPECT_TRUE(run) << (run ? "" : run.error().message);
  return run ? run->coverage : CoverageMasks{};
}

std::unique_ptr<RingsRenderer> createRings(std::shared_ptr<const TileStore> store,
                                           RingsOptions options) {
  Result<std::unique_ptr<RingsRenderer>> r =
      RingsRenderer::create(std::move(store), std::move(options));
  EXPECT_TRUE(r) << (r ? "" : r.error().message);
  return r ? std::move(r.value()) : nullptr;
}

RenderedFrame renderFrame(TerrainRenderer& renderer, const Aabb& bounds, const Camera& camera,
                          int width, int height, const RenderSettings& settings) {
  return renderFrame(renderer, ViewSetup::create(camera, bounds, width, height), settings);
}

RenderedFrame renderFrame(TerrainRenderer& renderer, const ViewSetup& view,
                          const RenderSettings& settings) {
  Result<OffscreenTarget> target = OffscreenTarget::create(view.width, view.height, 1);
  EXPECT_TRUE(target);
  if (!target) return {};
  target->begin({kSentinel[0], kSentinel[1], kSentinel[2]});
  renderer.prepare(view, settings);
  renderer.draw(view, settings);
  return {target->readRgb(), target->readDepth()};
}

std::filesystem::path writeLatLonTerrain(const std::filesystem::path& path, double west,
                                         double north, double step, int width, int height,
                                         double (*heights)(double latDeg, double lonDeg)) {
  HeightGrid grid(width, height);
  for (int j = 0; j < height; ++j) {
    for (int i = 0; i < width; ++i) grid.at(i, j) = float(heights(north - j * step, west + i * step));
  }
  grid.georef = {kWgs84Wkt, "WGS 84", true,
                 {west - 0.5 * step, step, 0.0, north + 0.5 * step, 0.0, -step}, true};
  EXPECT_TRUE(writeGeoTiff(grid, path));
  return path;
}

double sparseStoreRelief(double latDeg, double lonDeg) {
  return 2000.0 * std::sin(3.0 * latDeg * 0.01745) * std::cos(2.0 * lonDeg * 0.01745) +
         300.0 * std::sin(40.0 * latDeg * 0.01745) * std::sin(50.0 * lonDeg * 0.01745);
}

std::filesystem::path buildSparseGlobalStore(const std::filesystem::path& dir) {
  const std::filesystem::path coarse =
      writeLatLonTerrain(dir / "coarse.tif", -180.0, 90.0, 1.0, 360, 181, sparseStoreRelief);
  const std::filesystem::path fine =
      writeLatLonTerrain(dir / "fine.tif", 10.0, 42.0, 0.04, 51, 51, sparseStoreRelief);
  GlobalBuildOptions options;
  options.tileCells = 16;
  const std::filesystem::path store = dir / "store.tstore";
  Result<GlobalBuildReport> built = buildGlobalStore({coarse, fine}, store, options);
  EXPECT_TRUE(built) << (built ? "" : built.error().message);
  return store;
}

const GlobalStore& sparseGlobalStore() {
  static const std::shared_ptr<GlobalStore> store = [] {
    Result<std::shared_ptr<GlobalStore>> opened =
        GlobalStore::open(buildSparseGlobalStore(freshTestDir()));
    EXPECT_TRUE(opened);
    return opened ? opened.value() : nullptr;
  }();
  if (!store) throw std::runtime_error("the sparse global store could not be built");
  return *store;
}

}  // namespace tellus::test
