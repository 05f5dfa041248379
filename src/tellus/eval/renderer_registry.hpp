#pragma once
// The renderers `--algo NAME` can pick, by name. Each is created for one terrain: renderers that
// draw the full-resolution grid take the HeightGrid, streaming LOD renderers the tile store.
//
//   reference               every sample, no LOD, no culling (ground truth)
//   rings                   seed 000: rings of patches, GPU stitching, culling, GPU tile cache
//   rings-noculling         the same without frustum culling   (seed 000 Table 1 rows)
//   rings-brute             every patch at the finest level, with culling
//   rings-brute-noculling   every patch at the finest level, without culling
//   rings-incremental       seed 000's Base incremental: fractal codes decoded on the GPU with
//                           iterations by distance (needs a --codec fractal store)
#include <memory>
#include <string_view>
#include <vector>

#include "tellus/core/result.hpp"
#include "tellus/dem/height_grid.hpp"
#include "tellus/render/rings_renderer.hpp"
#include "tellus/render/terrain_renderer.hpp"
#include "tellus/tiles/tile_store.hpp"

namespace tellus {

struct RendererInputs {
  const HeightGrid* grid = nullptr;        // full-resolution heights
  std::shared_ptr<const TileStore> store;  // the same terrain as a tile store, when there is one
  // Streaming renderers load every tile a frame needs before drawing it (stills, tests) instead
  // of streaming tiles in over the following frames.
  bool waitForTiles = false;
  // Parameters of the rings renderers (patch size, rings, cache slots, uploads per frame...);
  // the name, culling, brute force, waiting and incremental decoding follow from the renderer
  // name and waitForTiles.
  RingsOptions rings;
};

std::vector<std::string_view> rendererNames();
// True for renderers that need RendererInputs::store.
bool rendererNeedsStore(std::string_view name);

// Memory a renderer allocates per sample of the full-resolution grid, on top of the grid itself,
// for the memory check before loading (memory_budget.hpp): the reference renderer's copy of
// every height on the GPU (in system memory on a software rasteriser) and its upload staging;
// the streaming renderers hold a fixed number of tiles whatever the grid.
double rendererBytesPerSample(std::string_view name);

// Needs a current GL context. Errors name the valid choices, or say what input is missing.
Result<std::unique_ptr<TerrainRenderer>> makeRenderer(std::string_view name,
                                                      const RendererInputs& inputs);

}  // namespace tellus
