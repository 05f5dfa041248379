// Seed 004's RAG (`--algo rag`, `rag-right`): rows, options, create().
#include "tellus/render/rag/rag_renderer.hpp"
#include "tellus/render/registry/renderer_registry.hpp"

namespace tellus {
namespace {

Result<std::unique_ptr<TerrainRenderer>> createRag(const RendererEntry& entry,
                                                   const RendererInputs& inputs,
                                                   const std::any& given) {
  if (!inputs.grid) return makeError("renderer '{}' needs the height grid", entry.name);
  // The tessellation follows from the row; exact counts from waiting (stills, tests).
  RagOptions options = std::any_cast<const RagOptions&>(given);
  options.name = std::string(entry.name);
  options.refinement.variant =
      entry.name == "rag-right" ? rag::Variant::RightAngled : rag::Variant::Oblique;
  options.exactCounts = inputs.waitForTiles;
  return madeRenderer(RagRenderer::create(*inputs.grid, options));
}

OptionSchema ragSchema() {
  using O = RagOptions;
  OptionSchema schema{"rag", "RAG", defaultsOf<O>(), {}};
  RendererOption coarse = numberOption<O>(
      "--rag-coarse", "coarse vertices",
      "RAG: vertices per side of the coarse mesh (the seed measures 20, 40, 80)", "",
      rag::kMinCoarseVertices, rag::kMaxCoarseVertices,
      [](O& o) -> int& { return o.coarseVertices; });
  coarse.panelMax = 160;
  RendererOption passes = numberOption<O>(
      "--rag-passes", "passes", "RAG: refinement passes per frame (with --rag-adaptive the most)",
      "", 0, kRagMaxPasses, [](O& o) -> int& { return o.passes; });
  RendererOption adaptive = flagOption<O>(
      "--rag-adaptive", "adaptive passes",
      "RAG: skip passes that added fewer than 5 % triangles in the previous frame",
      [](O& o) -> bool& { return o.adaptivePasses; });
  RendererOption pixels = numberOption<O>(
      "--rag-pixels", "split at",
      "rag: split an edge whose midpoint moves at least this many pixels on screen", "px", 0.01,
      1000.0, [](O& o) -> float& { return o.refinement.pixelEdge; });
  pixels.panelMin = 0.25;
  pixels.panelMax = 40.0;
  RendererOption probes = numberOption<O>(
      "--rag-probes", "edge probes",
      "rag: points of an edge whose screen error decides its split: 1 (the midpoint, the seed's) "
      "or 3 (its quarter points too)",
      "", 1, 3, [](O& o) -> int& { return o.refinement.edgeProbes; });
  probes.panelSteps = {1, 3};
  RendererOption heightDiff = numberOption<O>(
      "--rag-height-diff", "height difference",
      "rag-right: split an edge whose ends differ by more than this many metres", "m", 0.0,
      100000.0, [](O& o) -> float& { return o.refinement.heightDifferenceM; });
  heightDiff.panelMax = 500.0;
  RendererOption depthDetail = numberOption<O>(
      "--rag-depth-detail", "depth detail",
      "rag-right: weight of height differences at the far plane, 0 to 1 (1 near)", "", 0.0, 1.0,
      [](O& o) -> float& { return o.refinement.depthDetail; });
  RendererOption morph = numberOption<O>(
      "--rag-morph", "morph band",
      "rag: a new vertex enters at its edge's midpoint and reaches the map's height once the "
      "midpoint error passes the split threshold by this fraction of it (no pop when an edge "
      "splits); 0 for the seed's (at once)",
      "", 0.0, 1.0, [](O& o) -> float& { return o.refinement.morphBand; });
  RendererOption edgeLength = numberOption<O>(
      "--rag-edge-px", "split long edges",
      "rag: also split an edge whose length, seen face-on from its midpoint's distance, spans at "
      "least this many pixels (refines the ground near the eye to single samples); 0: never, "
      "the seed's",
      "px", 0.0, 10000.0, [](O& o) -> float& { return o.refinement.edgeLengthPx; });
  edgeLength.panelMax = 256.0;
  RendererOption noClip = flagOption<O>(
      "--rag-no-clip", "no early clipping",
      "RAG: keep triangles outside the view in every pass (no early clipping)",
      [](O& o) -> bool& { return o.refinement.earlyClip; }, false);
  RendererOption unaligned = flagOption<O>(
      "--rag-unaligned", "seed's coarse mesh",
      "RAG: the seed's coarse mesh (--rag-coarse vertices spread over the map, diagonals "
      "alternating, nearest samples) instead of cells of a power of two samples ending in the "
      "reference's own triangles; fine from above, hundreds of pixels off near the ground",
      [](O& o) -> bool& { return o.alignCoarseMesh; }, false);
  RendererOption maxMap = numberOption<O>(
      "--rag-max-map", "most map samples",
      "RAG: height-map samples a side at most (default: the GPU's texture limit); a larger "
      "terrain is refined against the finest pyramid level that fits",
      "", 3, 1 << 20, [](O& o) -> int& { return o.maxMapSamples; });
  maxMap.autoDefault = true;
  maxMap.inPanel = false;  // 0, the texture limit, is out of its range
  schema.options = {coarse, passes, adaptive, pixels, probes, heightDiff, depthDetail, morph, edgeLength, noClip, unaligned,
                    maxMap};
  return schema;
}

}  // namespace

const RendererFamily& ragRenderers() {
  static const RendererFamily family{
      ragSchema(),
      {{"rag", "recursive adaptive GPU refinement, partially oblique tessellations", "004",
        RendererSource::HeightGrid, 4.0, createRag},
       {"rag-right", "recursive adaptive GPU refinement, right-angled tessellations", "004",
        RendererSource::HeightGrid, 4.0, createRag, RendererWorld::Flat, true}},
      {},
      "the distance from its refined surface to the height map under each pixel"};
  return family;
}

}  // namespace tellus
