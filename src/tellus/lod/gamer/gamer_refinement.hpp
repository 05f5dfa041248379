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
#include <array>
#include <cstdint>
#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

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
};

// One coarse triangle to draw: cell (x, y), lower (0) or upper (1) half, and its pattern's
// interior depth (the LOD tint), packed for the GPU as (x | y << 16, half | interior << 8).
using Instance = glm::u32vec2;

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

  // Depth tags of every coarse vertex ((cellsX + 1) * (cellsY + 1), row by row from the south).
  void depthTags(const LodView& view, float targetPx, std::vector<std::uint8_t>& tags) const;
  // The coarse triangles to draw and their patterns.
  void select(const LodView& view, const GamerSettings& settings, const PatternPool& pool,
              const std::vector<std::uint8_t>& tags, Selection& out) const;

  // What the GPU's selection reads (render/gamer/gamer_gpu_selection.hpp): per coarse vertex its
  // errors at depths 0..maxDepth (metres, (maxDepth + 1) a vertex, row by row from the south),
  // per cell its height range, and half a coarse cell's diagonal (metres: a vertex's distance
  // is taken less that, its cells' nearest point).
  const std::vector<float>& vertexErrors() const { return vertexError_; }
  const std::vector<HeightRange>& cellHeights() const { return cellHeights_; }
  double cellRadiusM() const;

  // Corners (grid coordinates) of a coarse triangle in pattern order.
  std::array<glm::ivec2, 3> corners(int cx, int cy, int half) const;

  // CPU reference of the refined surface: every instance's pattern expanded, each vertex's
  // height read from the grid (bilinear between samples), as (x, y, height) triangles in grid
  // coordinates, three vertices each.
  std::vector<glm::vec3> refinedMesh(const PatternPool& pool, const Selection& selection) const;

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
