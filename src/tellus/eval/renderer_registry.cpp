#include "tellus/eval/renderer_registry.hpp"

#include <algorithm>
#include <array>

#include <fmt/format.h>

#include "tellus/render/globe/globe_reference_renderer.hpp"
#include "tellus/render/rag/rag_renderer.hpp"
#include "tellus/render/reference_renderer.hpp"
#include "tellus/render/rings/rings_renderer.hpp"

namespace tellus {
namespace {

Result<std::unique_ptr<TerrainRenderer>> createReference(const RendererEntry&,
                                                         const RendererInputs& inputs) {
  if (!inputs.grid) return makeError("the reference renderer needs the height grid");
  Result<ReferenceRenderer> renderer = ReferenceRenderer::create(*inputs.grid);
  if (!renderer) return renderer.error();
  return std::unique_ptr<TerrainRenderer>(
      std::make_unique<ReferenceRenderer>(std::move(renderer.value())));
}

Result<std::unique_ptr<TerrainRenderer>> createRings(const RendererEntry& entry,
                                                     const RendererInputs& inputs) {
  if (!inputs.store) {
    return makeError(
        "renderer '{}' streams from a tile store: give a .tstore as input (make one "
        "with 'tellus build DEM... -o NAME.tstore')",
        entry.name);
  }
  RingsOptions options = inputs.rings;
  options.name = std::string(entry.name);
  options.frustumCulling = !entry.name.ends_with("-noculling");
  options.bruteForce = entry.name.starts_with("rings-brute");
  options.waitForTiles = inputs.waitForTiles;
  options.incrementalFractal = entry.name == "rings-incremental";
  Result<std::unique_ptr<RingsRenderer>> rings = RingsRenderer::create(inputs.store, options);
  if (!rings) return rings.error();
  return std::unique_ptr<TerrainRenderer>(std::move(rings.value()));
}

Result<std::unique_ptr<TerrainRenderer>> createRag(const RendererEntry& entry,
                                                   const RendererInputs& inputs) {
  if (!inputs.grid) return makeError("renderer '{}' needs the height grid", entry.name);
  RagOptions options = inputs.rag;
  options.name = std::string(entry.name);
  options.refinement.variant =
      entry.name == "rag-right" ? rag::Variant::RightAngled : rag::Variant::Oblique;
  options.exactCounts = inputs.waitForTiles;
  Result<std::unique_ptr<RagRenderer>> renderer = RagRenderer::create(*inputs.grid, options);
  if (!renderer) return renderer.error();
  return std::unique_ptr<TerrainRenderer>(std::move(renderer.value()));
}

Result<std::unique_ptr<TerrainRenderer>> createRoam(const RendererEntry& entry,
                                                    const RendererInputs& inputs) {
  if (!inputs.grid) return makeError("renderer '{}' needs the height grid", entry.name);
  RoamOptions options = inputs.roam;
  options.name = std::string(entry.name);
  Result<std::unique_ptr<RoamRenderer>> renderer = RoamRenderer::create(*inputs.grid, options);
  if (!renderer) return renderer.error();
  return std::unique_ptr<TerrainRenderer>(std::move(renderer.value()));
}

Result<std::unique_ptr<TerrainRenderer>> createClipmaps(const RendererEntry& entry,
                                                        const RendererInputs& inputs) {
  if (!inputs.store) {
    return makeError("renderer '{}' reads its levels from a tile store: give a .tstore as input "
                     "(make one with 'tellus build DEM... -o NAME.tstore')",
                     entry.name);
  }
  ClipmapOptions options = inputs.clipmaps;
  options.name = std::string(entry.name);
  Result<std::unique_ptr<ClipmapRenderer>> renderer = ClipmapRenderer::create(inputs.store, options);
  if (!renderer) return renderer.error();
  return std::unique_ptr<TerrainRenderer>(std::move(renderer.value()));
}

Result<std::unique_ptr<TerrainRenderer>> createGamer(const RendererEntry& entry,
                                                     const RendererInputs& inputs) {
  if (!inputs.grid) return makeError("renderer '{}' needs the height grid", entry.name);
  GamerOptions options = inputs.gamer;
  options.name = std::string(entry.name);
  Result<std::unique_ptr<GamerRenderer>> renderer = GamerRenderer::create(*inputs.grid, options);
  if (!renderer) return renderer.error();
  return std::unique_ptr<TerrainRenderer>(std::move(renderer.value()));
}

Result<std::unique_ptr<TerrainRenderer>> createBdam(const RendererEntry& entry,
                                                    const RendererInputs& inputs) {
  if (!inputs.grid) return makeError("renderer '{}' needs the height grid", entry.name);
  BdamOptions options = inputs.bdam;
  options.name = std::string(entry.name);
  Result<std::unique_ptr<BdamRenderer>> renderer = BdamRenderer::create(*inputs.grid, options);
  if (!renderer) return renderer.error();
  return std::unique_ptr<TerrainRenderer>(std::move(renderer.value()));
}

Result<std::unique_ptr<TerrainRenderer>> createGiw(const RendererEntry& entry,
                                                   const RendererInputs& inputs) {
  if (!inputs.grid) return makeError("renderer '{}' needs the height grid", entry.name);
  GiwOptions options = inputs.giw;
  options.name = std::string(entry.name);
  Result<std::unique_ptr<GiwRenderer>> renderer = GiwRenderer::create(*inputs.grid, options);
  if (!renderer) return renderer.error();
  return std::unique_ptr<TerrainRenderer>(std::move(renderer.value()));
}

Result<std::unique_ptr<TerrainRenderer>> createGlobeReference(const RendererEntry& entry,
                                                              const RendererInputs& inputs) {
  if (!inputs.grid) return makeError("renderer '{}' needs the height grid", entry.name);
  Result<GlobeReferenceRenderer> renderer =
      GlobeReferenceRenderer::create(*inputs.grid, inputs.geoid, inputs.drape);
  if (!renderer) return renderer.error();
  return std::unique_ptr<TerrainRenderer>(
      std::make_unique<GlobeReferenceRenderer>(std::move(renderer.value())));
}

Result<std::unique_ptr<TerrainRenderer>> createRingo(const RendererEntry& entry,
                                                     const RendererInputs& inputs) {
  if (!inputs.globalStore) {
    return makeError("renderer '{}' streams from a global store: give one built with 'tellus "
                     "build --global SOURCES... -o earth.tstore'",
                     entry.name);
  }
  RingoOptions options = inputs.ringo;
  options.waitForBlocks = inputs.waitForTiles;
  options.geoid = inputs.geoid;
  Result<std::unique_ptr<RingoRenderer>> renderer =
      RingoRenderer::create(inputs.globalStore, options);
  if (!renderer) return renderer.error();
  return std::unique_ptr<TerrainRenderer>(std::move(renderer.value()));
}

Result<std::unique_ptr<TerrainRenderer>> createSpiral(const RendererEntry& entry,
                                                      const RendererInputs& inputs) {
  if (!inputs.globalStore) {
    return makeError("renderer '{}' draws a global store: give one built with 'tellus build "
                     "--global SOURCES... -o earth.tstore'",
                     entry.name);
  }
  SpiralOptions options = inputs.spiral;
  options.waitForHeights = inputs.waitForTiles;
  options.geoid = inputs.geoid;
  Result<std::unique_ptr<SpiralRenderer>> renderer =
      SpiralRenderer::create(inputs.globalStore, options);
  if (!renderer) return renderer.error();
  return std::unique_ptr<TerrainRenderer>(std::move(renderer.value()));
}

Status needStacks(const RendererEntry& entry, const RendererInputs& inputs) {
  if (!inputs.stacks || inputs.stacks->empty()) {
    return makeError("renderer '{}' draws material stacks: give a .tstack as input (make one with "
                     "'tellus stacks build DEM -o NAME.tstack')",
                     entry.name);
  }
  return {};
}

Result<std::unique_ptr<TerrainRenderer>> createStacksFull(const RendererEntry& entry,
                                                          const RendererInputs& inputs) {
  if (Status ok = needStacks(entry, inputs); !ok) return ok.error();
  Result<std::unique_ptr<StacksFullRenderer>> renderer =
      StacksFullRenderer::create(inputs.stacks->front(), inputs.stacksOptions);
  if (!renderer) return renderer.error();
  return std::unique_ptr<TerrainRenderer>(std::move(renderer.value()));
}

Result<std::unique_ptr<TerrainRenderer>> createStacksLod(const RendererEntry& entry,
                                                         const RendererInputs& inputs) {
  if (Status ok = needStacks(entry, inputs); !ok) return ok.error();
  Result<std::unique_ptr<StacksLodRenderer>> renderer =
      StacksLodRenderer::create(*inputs.stacks, inputs.stacksOptions, inputs.waitForTiles);
  if (!renderer) return renderer.error();
  return std::unique_ptr<TerrainRenderer>(std::move(renderer.value()));
}

constexpr std::array<RendererEntry, 18> kTable{{
    {"reference", "every sample as a vertex, no LOD, no culling: the ground truth", "-",
     RendererSource::HeightGrid, 8.0, createReference},
    {"rings", "rings of patches around the viewer, GPU stitching, frustum culling", "000",
     RendererSource::TileStore, 0.0, createRings},
    {"rings-noculling", "rings without frustum culling (seed 000 Table 1)", "000",
     RendererSource::TileStore, 0.0, createRings, RendererWorld::Flat, true},
    {"rings-brute", "every patch at the finest level, with culling (seed 000 Table 1)", "000",
     RendererSource::TileStore, 0.0, createRings, RendererWorld::Flat, true},
    {"rings-brute-noculling", "every patch at the finest level, no culling (seed 000 Table 1)",
     "000", RendererSource::TileStore, 0.0, createRings, RendererWorld::Flat, true},
    {"rings-incremental",
     "rings on a fractal store, tiles decoded on the GPU with iterations by distance", "000",
     RendererSource::TileStore, 0.0, createRings, RendererWorld::Flat, true},
    {"rag", "recursive adaptive GPU refinement, partially oblique tessellations", "004",
     RendererSource::HeightGrid, 4.0, createRag},
    {"rag-right", "recursive adaptive GPU refinement, right-angled tessellations", "004",
     RendererSource::HeightGrid, 4.0, createRag, RendererWorld::Flat, true},
    {"roam",
     "ROAM: a triangle bintree split and merged on the CPU by two priority queues carried from "
     "frame to frame, nested error bounds, forced splits; the mesh streamed each frame",
     "004", RendererSource::HeightGrid, 6.0, createRoam},
    {"clipmaps",
     "GPU geometry clipmaps: nested grids centred on the viewer, heights in toroidal textures "
     "updated from the tile store as it moves, geomorphing at level borders",
     "004", RendererSource::TileStore, 0.0, createClipmaps},
    {"gamer",
     "GAMeR: depth tags at the coarse vertices from distance and local error, a precomputed "
     "refinement pattern per coarse triangle (one per edge-depth triple), instanced by one "
     "multi-draw-indirect, heights from the grid texture",
     "004", RendererSource::HeightGrid, 4.0, createGamer},
    {"bdam",
     "BDAM: a bintree of TIN patches simplified offline with locked borders (tellus build --bdam), "
     "traversed to a screen-space error by diamonds, patches read on demand into a GPU cache",
     "004", RendererSource::HeightGrid, 4.0, createBdam},
    {"giw",
     "geometry image warping: a quad mesh over the view's footprint warped each frame by an "
     "importance map (distance, slope, frustum), rows then columns, sent to the GPU each frame",
     "004", RendererSource::HeightGrid, 4.0, createGiw},
    {"globe-reference",
     "every sample of a lat/lon DEM on the WGS84 ellipsoid, no LOD: the globe's ground truth",
     "-", RendererSource::HeightGrid, 112.0, createGlobeReference, RendererWorld::Globe},
    {"ringo",
     "nested rings of blocks on the WGS84 ellipsoid, static GPU buffers, parallel reorganisation",
     "002", RendererSource::GlobalStore, 0.0, createRingo, RendererWorld::Globe},
    {"spiral",
     "one static spiral re-centred under the camera and wrapped onto the globe (or flat, "
     "hyperbolic, dome), heights by vertex texture fetch, occlusion-query radii",
     "001", RendererSource::GlobalStore, 0.0, createSpiral, RendererWorld::Globe},
    {"stacks-full",
     "material stacks with arches, overhangs and caves quadrangulated whole at the finest level "
     "on the GPU (density, smoothing, dual contouring), one indirect draw: the 3D ground truth",
     "003", RendererSource::StackTerrain, 0.0, createStacksFull},
    {"stacks",
     "octree LOD over the stack MipMap: nodes by screen-space extent, stitched across levels, "
     "meshes cached in one GPU pool (LRU), made by the GPU pipeline at most K a frame",
     "003", RendererSource::StackTerrain, 0.0, createStacksLod},
}};

}  // namespace

std::span<const RendererEntry> rendererTable() {
  return kTable;
}

const RendererEntry* findRenderer(std::string_view name) {
  const auto found = std::find_if(kTable.begin(), kTable.end(),
                                  [&](const RendererEntry& e) { return e.name == name; });
  return found == kTable.end() ? nullptr : &*found;
}

std::vector<std::string_view> rendererNames() {
  std::vector<std::string_view> names;
  for (const RendererEntry& entry : kTable) names.push_back(entry.name);
  return names;
}

bool rendererNeedsStore(std::string_view name) {
  const RendererEntry* entry = findRenderer(name);
  return entry && entry->source == RendererSource::TileStore;
}

bool rendererNeedsGlobalStore(std::string_view name) {
  const RendererEntry* entry = findRenderer(name);
  return entry && entry->source == RendererSource::GlobalStore;
}

bool rendererNeedsStacks(std::string_view name) {
  const RendererEntry* entry = findRenderer(name);
  return entry && entry->source == RendererSource::StackTerrain;
}

bool rendererDrawsGlobe(std::string_view name) {
  const RendererEntry* entry = findRenderer(name);
  return entry && entry->world == RendererWorld::Globe;
}

double rendererBytesPerSample(std::string_view name) {
  const RendererEntry* entry = findRenderer(name);
  return entry ? entry->bytesPerSample : 0.0;
}

std::string rendererHelp() {
  return fmt::format("Renderer: {} (`tellus renderers` lists them with what each needs)",
                     fmt::join(rendererNames(), ", "));
}

Result<std::unique_ptr<TerrainRenderer>> makeRenderer(std::string_view name,
                                                      const RendererInputs& inputs) {
  const RendererEntry* entry = findRenderer(name);
  if (!entry) {
    return makeError("unknown renderer '{}' (available: {})", name,
                     fmt::join(rendererNames(), ", "));
  }
  return entry->create(*entry, inputs);
}

}  // namespace tellus
