// The renderer families, in the order `tellus renderers`, `--algo all` and the viewer list
// them. Adding an algorithm: its folder's <algo>_entry.cpp defines one family function, and
// it gets one line here.
#include "tellus/render/registry/renderer_list.hpp"

namespace tellus {

const RendererFamily& referenceRenderers();
const RendererFamily& ringsRenderers();
const RendererFamily& ragRenderers();
const RendererFamily& roamRenderers();
const RendererFamily& clipmapRenderers();
const RendererFamily& gamerRenderers();
const RendererFamily& bdamRenderers();
const RendererFamily& giwRenderers();
const RendererFamily& globeReferenceRenderers();
const RendererFamily& ringoRenderers();
const RendererFamily& spiralRenderers();
const RendererFamily& stackRenderers();

std::vector<const RendererFamily*> listRendererFamilies() {
  return {
      &referenceRenderers(),  // render/reference/reference_entry.cpp
      &ringsRenderers(),      // render/rings/rings_entry.cpp (seed 000)
      &ragRenderers(),        // render/rag/rag_entry.cpp (seed 004)
      &roamRenderers(),       // render/roam/roam_entry.cpp (seed 004)
      &clipmapRenderers(),    // render/clipmaps/clipmaps_entry.cpp (seed 004)
      &gamerRenderers(),      // render/gamer/gamer_entry.cpp (seed 004)
      &bdamRenderers(),       // render/bdam/bdam_entry.cpp (seed 004)
      &giwRenderers(),        // render/giw/giw_entry.cpp (seed 004)
      &globeReferenceRenderers(),  // render/globe/globe_reference_entry.cpp
      &ringoRenderers(),      // render/ringo/ringo_entry.cpp (seed 002)
      &spiralRenderers(),     // render/spiral/spiral_entry.cpp (seed 001)
      &stackRenderers(),      // render/stacks/stacks_entry.cpp (seed 003)
  };
}

}  // namespace tellus
