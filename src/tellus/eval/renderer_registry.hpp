#pragma once
// The renderers `--algo NAME` can pick: one table, read by the command-line help, the
// viewer's renderer list, the memory check before loading and makeRenderer(). Adding a
// renderer means adding one row to rendererTable() in renderer_registry.cpp.
//
//   reference               every sample, no LOD, no culling (ground truth)
//   rings                   seed 000: rings of patches, GPU stitching, culling, GPU tile cache
//   rings-noculling         the same without frustum culling   (seed 000 Table 1 rows)
//   rings-brute             every patch at the finest level, with culling
//   rings-brute-noculling   every patch at the finest level, without culling
//   rings-incremental       seed 000's Base incremental (needs a --codec fractal store)
//   rag                     seed 004: recursive adaptive GPU refinement, oblique tessellations
//   rag-right               seed 004: the same with right-angled tessellations
//   roam                    seed 004: ROAM, the CPU bintree split and merged by two queues
//   clipmaps                seed 004: GPU geometry clipmaps from the tile store
//   gamer                   seed 004: GAMeR, adaptive refinement patterns instanced per coarse triangle
//   bdam                    seed 004: BDAM, precomputed TIN patches on a bintree, from a patch file
//   giw                     seed 004: geometry image warping, a quad mesh warped by importance each frame
//   globe-reference         every sample of a lat/lon DEM on the ellipsoid (the globe's truth)
//   ringo                   seed 002: nested rings of blocks on the ellipsoid from a global store
//   spiral                  seed 001: one static spiral re-centred under the camera, heights by vertex texture fetch
//   stacks-full             seed 003: a stack terrain quadrangulated whole on the GPU (3D ground truth)
//   stacks                  seed 003: octree LOD over the stack MipMap, stitched, cached, amortised
#include <memory>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "tellus/core/result.hpp"
#include "tellus/dem/drape_image.hpp"
#include "tellus/dem/height_grid.hpp"
#include "tellus/render/rag/rag_renderer.hpp"
#include "tellus/render/ringo/ringo_renderer.hpp"
#include "tellus/render/spiral/spiral_renderer.hpp"
#include "tellus/render/stacks/stacks_full_renderer.hpp"
#include "tellus/render/stacks/stacks_lod_renderer.hpp"
#include "tellus/render/rings/rings_renderer.hpp"
#include "tellus/render/clipmaps/clipmap_renderer.hpp"
#include "tellus/render/gamer/gamer_renderer.hpp"
#include "tellus/render/bdam/bdam_renderer.hpp"
#include "tellus/render/giw/giw_renderer.hpp"
#include "tellus/render/roam/roam_renderer.hpp"
#include "tellus/render/terrain_renderer.hpp"
#include "tellus/tiles/tile_store.hpp"

namespace tellus {

class Geoid;

struct RendererInputs {
  const HeightGrid* grid = nullptr;        // full-resolution heights
  std::shared_ptr<const TileStore> store;  // the same terrain as a tile store, when there is one
  // Streaming renderers load every tile a frame needs before drawing it (stills, tests) instead
  // of streaming tiles in over the following frames; RAG reads its pass counts at the end of
  // each frame (no frame drawn from overflowed buffers).
  bool waitForTiles = false;
  // Parameters of the rings renderers (patch size, rings, cache slots, uploads per frame...);
  // the name, culling, brute force, waiting and incremental decoding follow from the row.
  RingsOptions rings;
  // Parameters of RAG (coarse mesh, passes, thresholds); the variant follows from the row.
  RagOptions rag;
  // Parameters of ROAM (error target, triangle and time budgets, block size).
  RoamOptions roam;
  // Parameters of the geometry clipmaps (level size, levels, transition width, culling).
  ClipmapOptions clipmaps;
  // Parameters of GAMeR (pattern depth, error target, culling).
  GamerOptions gamer;
  // Parameters of BDAM (its patch file, error target, cache, culling).
  BdamOptions bdam;
  // Parameters of geometry image warping (image size, importance weights).
  GiwOptions giw;
  // Globe renderers: the geoid that turns heights above the geoid into ellipsoidal ones (null:
  // heights are drawn as ellipsoidal).
  const Geoid* geoid = nullptr;
  // Globe renderers: a colour map draped over the globe instead of the hypsometric tint.
  const DrapeImage* drape = nullptr;
  // The global store, for the renderers that stream from one (RINGO, the spiral).
  std::shared_ptr<const GlobalStore> globalStore;
  // Parameters of RINGO (rings, uploads per frame); waiting and the geoid follow from above.
  RingoOptions ringo;
  // Parameters of the spiral globe (spiral, projection, radius control); waiting and the
  // geoid follow from above.
  SpiralOptions spiral;
  // Stack-terrain renderers: every level of a .tstack (level 0, the finest, first), and the
  // pipeline's and the octree's parameters.
  const std::vector<StackTerrain>* stacks = nullptr;
  StacksRenderOptions stacksOptions;
};

// The world a renderer draws in, and so the cameras it takes.
enum class RendererWorld {
  Flat,   // metres east and north of the DEM's south-west sample (Camera, ViewSetup::create)
  Globe,  // ECEF on the WGS84 ellipsoid (GeoCamera, geoViewSetup)
};

// What a renderer draws from.
enum class RendererSource {
  HeightGrid,  // the full-resolution grid (from any DEM or store)
  TileStore,   // streams from a .tstore
  GlobalStore,  // streams from a global .tstore (tellus build --global)
  StackTerrain,  // material stacks (.tstack, tellus stacks build): 3D terrain
};

struct RendererEntry {
  std::string_view name;
  std::string_view description;  // one line
  std::string_view seed;         // the seed paper it implements: "000", "004", or "-"
  RendererSource source = RendererSource::HeightGrid;
  // Memory allocated per sample of the full-resolution grid on top of the grid itself, for the
  // memory check before loading (memory_budget.hpp): heights copied to the GPU (system memory
  // on a software rasteriser) and upload staging; 0 for renderers holding a fixed tile budget.
  double bytesPerSample = 0.0;
  Result<std::unique_ptr<TerrainRenderer>> (*create)(const RendererEntry& entry,
                                                     const RendererInputs& inputs) = nullptr;
  RendererWorld world = RendererWorld::Flat;
  // A variant of another row (a seed table's ablation, another tessellation): `--algo all`
  // leaves it out, so that each algorithm appears once.
  bool variant = false;
};

std::span<const RendererEntry> rendererTable();
// nullptr when there is no such renderer.
const RendererEntry* findRenderer(std::string_view name);

std::vector<std::string_view> rendererNames();
// True for renderers that need RendererInputs::store.
bool rendererNeedsStore(std::string_view name);
// True for renderers that need RendererInputs::globalStore (and no grid).
bool rendererNeedsGlobalStore(std::string_view name);
// True for renderers that draw material stacks (RendererInputs::stacks).
bool rendererNeedsStacks(std::string_view name);
// True for renderers that draw on the globe (they take geo cameras).
bool rendererDrawsGlobe(std::string_view name);
double rendererBytesPerSample(std::string_view name);
// "Renderer: NAME, NAME, ... (`tellus renderers` ...)" for an --algo option's help: the names
// only; `tellus renderers` prints the table.
std::string rendererHelp();

// Needs a current GL context. Errors name the valid choices, or say what input is missing.
Result<std::unique_ptr<TerrainRenderer>> makeRenderer(std::string_view name,
                                                      const RendererInputs& inputs);

}  // namespace tellus
