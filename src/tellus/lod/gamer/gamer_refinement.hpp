#pragma once
// GAMeR's per-frame work on the CPU (seed 004 section 2.5): a depth tag for every vertex of the
// coarse mesh from the viewer, then, for every coarse triangle in the frustum, the pattern of its
// three edge depths. The GPU draws each pattern once, instanced over the coarse triangles that
// use it (one multi-draw-indirect command a pattern).
//
// Coarse mesh: cells of 2^maxDepth grid cells (the last column and row narrower when the grid
// does not divide), each split along its south-west / north-east diagonal into a lower triangle
// (SW, SE, NE) and an upper one (NE, NW, SW), corners in pattern order (0, 1, 2): corner 1 is
// the right angle and edge 2 the diagonal in both. Grid
// coordinates: x samples east of the western column, y samples north of the southern row.
//
// Depth tag of a vertex: the smallest depth d whose sampling (2^d segments a coarse edge) has an
// error, among the cells around the vertex, under the target once projected at the vertex's
// distance (less half a cell diagonal: the cell's nearest point). An edge's depth is the larger
// tag of its two ends, so the two triangles sharing an edge agree on it (no crack); the
// pattern's interior is refined to the smallest of its three edge depths.
//
// Geomorph (the seed's future work, done CDLOD-style): each vertex also gets a continuous morph
// depth tau in (tag - 1, tag] (lower where depths of equal error are skipped together), which
// runs from tag - 1, at the distance where depth tag - 1 stops meeting the target, to tag over
// `morphBand` of the way to the distance where depth tag stops meeting it. An edge's morph
// depth is the larger of its ends'; inside a triangle the three edges' are blended, each
// weighing most near its edge. A pattern vertex takes its height from the uniform
// depth-floor(D) sampling of the coarse triangle, blended towards the depth-floor(D) + 1
// sampling by D's fraction: a vertex that appears when a tag goes up starts on the coarser
// surface and slides to its own sample as the viewer comes closer. Vertices on an edge depend
// only on that edge (no crack). With errors that halve per depth the projected error bound
// stays the target (the blend of two bounds at a distance between them). What still pops: where
// a switch changes a pattern's interior depth next to an edge that is still morphing, the band
// between them is triangulated differently before and after (docs/gamer.md).
#include <array>
#include <cstdint>
#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include "tellus/core/aabb.hpp"
#include "tellus/core/result.hpp"
#include "tellus/dem/height_grid.hpp"
#include "tellus/lod/gamer/gamer_patterns.hpp"
#include "tellus/lod/lod_view.hpp"

namespace tellus::gamer {

struct GamerSettings {
  int maxDepth = 5;        // patterns up to 2^maxDepth segments an edge; coarse cells of 2^maxDepth cells
  float targetPx = 2.0f;   // screen-space error target of the depth tags, pixels (a conservative
                           // estimate: 2 px measures about 1 px at p99 on the Korea flyover)
  bool culling = true;     // leave out coarse triangles outside the frustum
  float morphBand = 0.5f;  // share of each depth's distance range over which its new vertices
                           // slide from the coarser surface, (0, 1]; 0: no geomorph (patterns pop)
};

// Morph depths travel to the GPU as 16-bit fixed point: depth * kMorphDepthScale.
inline constexpr float kMorphDepthScale = 8192.0f;

// A vertex's depth tag and its continuous morph depth (see above).
struct DepthTags {
  std::vector<std::uint8_t> tag;    // per coarse vertex, row by row from the south
  std::vector<float> morphDepth;    // per coarse vertex: tag - 1 < depth <= tag (tag 0: 0);
                                    // maxDepth everywhere without the geomorph (band 0)
};

// The morph depth of a vertex with depth tag `tag` at `distanceM`: tag - 1 at the distance where
// depth tag - 1 meets the target exactly, rising linearly to tag over `band` of the way to the
// distance where depth tag does (from the tag beyond that distance, lower than tag - 1 where
// depths of equal error are skipped together, so the morph depth never jumps). `errorsM` are the vertex's errors at depths 0..maxDepth
// (non-increasing), `scale` the pixels a metre of error covers at 1 m.
float morphDepthAt(const float* errorsM, int tag, double scale, double distanceM, float targetPx, float band);

// One coarse triangle to draw: cell (x, y), lower (0) or upper (1) half, its pattern's interior
// depth (the LOD tint) and its three edges' morph depths, packed for the GPU as
// (x | y << 16, half | interior << 8, D0 | D1 << 16, D2), D in 1 / kMorphDepthScale.
using Instance = glm::u32vec4;

// What select() chose: the instances sorted by pattern, and each pattern's run of them.
struct Selection {
  std::vector<Instance> instances;
  std::vector<std::uint32_t> firstInstance;  // per pattern (PatternPool::patternIndex)
  std::vector<std::uint32_t> instanceCount;  // per pattern
  std::uint64_t triangles = 0;               // summed over the instances' patterns
  std::uint32_t coarseTriangles = 0;         // in the frustum (drawn)
};

class CoarseTerrain {
 public:
  // Precomputes every cell's sampling error at each depth and its height range (all cores).
  // `grid` must outlive the terrain. Errors: a grid under 2 x 2, maxDepth out of range.
  static Result<CoarseTerrain> create(const HeightGrid& grid, int maxDepth);

  int maxDepth() const { return maxDepth_; }
  int cellsX() const { return cellsX_; }
  int cellsY() const { return cellsY_; }
  // Grid coordinates of coarse vertex (i, j), 0 <= i <= cellsX, 0 <= j <= cellsY.
  glm::ivec2 vertexSample(int i, int j) const;
  // The largest vertical error, metres, of drawing cell (cx, cy) with 2^depth segments an edge.
  float cellErrorM(int cx, int cy, int depth) const {
    return cellError_[(std::size_t(cy) * std::size_t(cellsX_) + std::size_t(cx)) * std::size_t(maxDepth_ + 1) + std::size_t(depth)];
  }
  // World box of cell (cx, cy) (heights not exaggerated).
  Aabb cellBounds(int cx, int cy) const;
  const HeightGrid& grid() const { return *grid_; }

  // Depth tags and morph depths of every coarse vertex ((cellsX + 1) * (cellsY + 1)).
  void depthTags(const LodView& view, float targetPx, float morphBand, DepthTags& tags) const;
  // The coarse triangles to draw, their patterns and edge morph depths.
  void select(const LodView& view, const GamerSettings& settings, const PatternPool& pool,
              const DepthTags& tags, Selection& out) const;

  // What the GPU's selection reads (render/gamer/gamer_gpu_selection.hpp): per coarse vertex its
  // errors at depths 0..maxDepth (metres, (maxDepth + 1) a vertex, row by row from the south;
  // each the largest of its cells' at that depth or finer, so they never grow with depth),
  // per cell its height range, and half a coarse cell's diagonal (metres: a vertex's distance
  // is taken less that, its cells' nearest point).
  const std::vector<float>& vertexErrors() const { return vertexError_; }
  const std::vector<HeightRange>& cellHeights() const { return cellHeights_; }
  double cellRadiusM() const;

  // Corners (grid coordinates) of a coarse triangle in pattern order.
  std::array<glm::ivec2, 3> corners(int cx, int cy, int half) const;

  // CPU reference of the refined surface: every instance's pattern expanded, each vertex's
  // height its morphed height (morphedHeight), as (x, y, height) triangles in grid coordinates,
  // three vertices each.
  std::vector<glm::vec3> refinedMesh(const PatternPool& pool, const Selection& selection) const;
  // The height of lattice vertex (a, b) of an instance's pattern (shaders/gamer/gamer.vert does
  // the same): its edge's morph depth on an edge, the three blended inside; the uniform
  // sampling at that depth's floor blended towards the next by its fraction. Each sampling reads
  // the grid (bilinear) at its lattice points; on an edge it interpolates along the edge from its
  // lexicographically smaller end, so both triangles on the edge compute the same value.
  float morphedHeight(const Instance& instance, int latticeSteps, int a, int b) const;

 private:
  const HeightGrid* grid_ = nullptr;
  int maxDepth_ = 0;
  int cellsX_ = 0, cellsY_ = 0;
  std::vector<float> cellError_;  // per cell, per depth 0..maxDepth
  std::vector<HeightRange> cellHeights_;
  std::vector<float> vertexError_;  // per coarse vertex, per depth: max over its cells
};

// Height of the grid at grid coordinates (x east, y north from the south-west), bilinear.
float heightAtGrid(const HeightGrid& grid, double x, double y);

}  // namespace tellus::gamer
