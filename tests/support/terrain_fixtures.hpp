#pragma once
// Shared fixtures of the GPU tests that render terrain along paths: a procedural terrain written
// as a projected GeoTIFF (input for tile-store builds), quality-run options, the reference
// renderer's terrain coverage along a path (what crack detection compares a LOD renderer's
// frames with), and making a rings renderer and rendering one frame of it.
#include <cstdint>
#include <filesystem>
#include <memory>
#include <vector>

#include "tellus/core/camera.hpp"
#include "tellus/core/depth_image.hpp"
#include "tellus/core/rgb_image.hpp"
#include "tellus/dem/height_grid.hpp"
#include "tellus/dem/terrain_generator.hpp"
#include "tellus/eval/path_benchmark.hpp"
#include "tellus/render/rings/rings_renderer.hpp"
#include "tellus/tiles/global_store.hpp"
#include "tellus/tiles/tile_store.hpp"

namespace tellus::test {

// generateTerrain(params), georeferenced in UTM 52N (EPSG:32652) with its corner at
// (300 km, 4200 km) and params.spacingM between samples, written to `geotiff`. Fails the
// current test if the file cannot be written.
HeightGrid writeGeneratedTerrain(const TerrainParams& params, const std::filesystem::path& geotiff);

// A tile store of generateTerrain(params) (written as dir/terrain.tif, built as
// dir/terrain.tstore in tiles of tileSize cells, opened) and its level 0 as the store holds it
// (heights quantised): what renderers of the store and the reference of its grid both see.
// Fails the current test (store null) if it cannot be built.
struct GeneratedStore {
  std::shared_ptr<const TileStore> store;
  HeightGrid level0;
};
GeneratedStore buildGeneratedStore(const TerrainParams& params, const std::filesystem::path& dir,
                                   int tileSize);

// A WGS 84 latitude/longitude GeoTIFF of heights(lat, lon) at pixel centres running from
// (north, west) in `step`-degree steps, width x height samples.
std::filesystem::path writeLatLonTerrain(const std::filesystem::path& path, double west,
                                         double north, double step, int width, int height,
                                         double (*heights)(double latDeg, double lonDeg));

// The relief of sparseGlobalStore's sources: kilometres of smooth relief with 300 m ripples.
double sparseStoreRelief(double latDeg, double lonDeg);

// A sparse global store of 16-cell tiles, built once into dir / "store.tstore": a whole-globe
// source at 1 degree (feeding depth 3) and a fine one at 0.04 degree over 10..12 E, 40..42 N
// (feeding depth 7), both of sparseStoreRelief: tiles deeper than 3 exist only over (and just
// around) the fine area. Fails the current test if it cannot be built.
std::filesystem::path buildSparseGlobalStore(const std::filesystem::path& dir);
// That store, built and opened once per process; throws when it cannot be built.
const GlobalStore& sparseGlobalStore();

// Path-run options for quality measurements: frames of width x height, `warmupFrames` drawn
// first, screen-space error and cracks measured.
PathRunOptions qualityRun(int width, int height, int warmupFrames);

// Per-frame coverage masks of the reference renderer on `grid` along `cameras`, rendered with
// `options` (no frames kept).
CoverageMasks referenceCoverage(const HeightGrid& grid, const std::vector<Camera>& cameras,
                                const PathRunOptions& options);

// RingsRenderer::create; fails the current test (and returns nullptr) when it cannot.
std::unique_ptr<RingsRenderer> createRings(std::shared_ptr<const TileStore> store,
                                           RingsOptions options);

// The background of renderFrame(): magenta, which terrain never is.
inline constexpr std::uint8_t kSentinel[3] = {255, 0, 255};

struct RenderedFrame {
  RgbImage colour;
  DepthImage depth;
};
// One frame (prepare, draw) of `renderer` from `camera`, width x height, one sample per pixel,
// over kSentinel; `bounds` sets the clip range.
RenderedFrame renderFrame(TerrainRenderer& renderer, const Aabb& bounds, const Camera& camera,
                          int width, int height, const RenderSettings& settings = {});
// The same from a view set up by the caller (globe views).
RenderedFrame renderFrame(TerrainRenderer& renderer, const ViewSetup& view,
                          const RenderSettings& settings = {});

}  // namespace tellus::test
