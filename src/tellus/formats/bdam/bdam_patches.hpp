#pragma once
// BDAM's precomputed patches (seed 004 section 2.2; Cignoni et al. 2003): one TIN per node of
// the triangle bintree (bdam_bintree.hpp) down to a leaf level, each simplified from its two
// children with a quadric error metric (meshoptimizer) while the vertices on its legs stay
// locked and those on its hypotenuse may only collapse along it, together with the patch on the
// other side (the seed's Figure 2: square sub-meshes, locked contours, a locked diagonal that
// is simplified once, as the square's diagonal, and then kept).
//
// Why neighbours match (crack-free by construction): a level-l hypotenuse is decided at level
// l, as the diagonal of the square being simplified, both sides collapsing together (one vertex
// set); at level l - 1 it is a leg, on the square's border, locked. A conforming cut (diamonds
// split together) puts side by side only patches of one level, or of levels l and l + 1 across a
// level-l leg (= a level-(l + 1) hypotenuse): both see that edge's one vertex set. (Coarser
// levels re-simplify the line as part of a longer hypotenuse, but a conforming cut never puts
// such a patch beside the finer ones.) The leaves are made the same way from the grid's own
// triangles (the bintree's 4-8 mesh at half-cell level), so their legs keep every sample.
//
// Errors: a patch's object-space error is the largest vertical distance between it and the grid
// samples it covers (the seed's geometric error), metres.
#include <cstdint>
#include <vector>

#include <glm/vec2.hpp>

#include "tellus/formats/bdam/bdam_bintree.hpp"
#include "tellus/core/result.hpp"
#include "tellus/dem/height_grid.hpp"

namespace tellus::bdam {

struct BuildSettings {
  int leafLog2 = 13;            // a leaf patch covers 2^leafLog2 half-cells of the grid
  int patchTriangles = 1024;    // triangles a patch is simplified to
};

struct Patch {
  NodeId node = 0;
  std::vector<glm::ivec2> positions;   // grid samples
  std::vector<float> heights;          // metres, one per position
  std::vector<std::uint16_t> indices;  // counter-clockwise triangles
  float errorM = 0.0f;
  float minZ = 0.0f, maxZ = 0.0f;      // of the vertices, metres
};

struct Hierarchy {
  int gridWidth = 0, gridHeight = 0;
  double spacingXM = 1.0, spacingYM = 1.0;
  int domainLog2 = 0;
  int leafLevel = 0;            // the finest patches' level
  std::vector<Patch> patches;   // by node id; empty nodes (outside the grid) have none
};

// Builds every patch on all cores (a progress line on a terminal). Errors: a grid under 2 x 2
// or over 65537 samples a side (patches store 16-bit coordinates), settings out of range.
Result<Hierarchy> buildHierarchy(const HeightGrid& grid, const BuildSettings& settings);

// The largest vertical distance, metres, between the patch (positions, heights, indices) and
// the grid samples inside its triangles.
float patchErrorM(const HeightGrid& grid, const std::vector<glm::ivec2>& positions,
                  const std::vector<float>& heights, const std::vector<std::uint16_t>& indices);

// Height of grid sample (x, y), y north from the southern row.
inline float sampleHeight(const HeightGrid& grid, glm::ivec2 p) { return grid.at(p.x, grid.height - 1 - p.y); }

}  // namespace tellus::bdam
