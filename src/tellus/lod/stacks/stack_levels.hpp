#pragma once
// The levels the octree LOD renderer of stack terrain draws from (seed 003, section 3.3: an
// octree level is a level of the stacks' MipMap): every level of a .tstack pyramid quantised
// for the quadrangulation pipeline, with the geometry that makes the levels nest, and per
// column the range of heights where any finer level has a surface. GL-free.
//
// Nesting: level k has stacks 2^k finest stacks apart and density cells 2^k * cellM high, and
// its sample (x, y, z) lies on sample 2^k * (x, y, z) of level 0, so that a coarser node's
// densities can be point-sampled on a finer node's border (stitching, section 3.4). Level 0
// samples its cell z at height (z + 1/2) * cellM; level k's cells are shifted down by
// (2^k - 1) / 2 * cellM (QuantisedStacks::baseM) to put its sample z at (2^k z + 1/2) * cellM.
#include <vector>

#include "tellus/core/result.hpp"
#include "tellus/formats/stacks/material_stack.hpp"
#include "tellus/formats/stacks/quadrangulation.hpp"
#include "tellus/formats/stacks/quantised_stacks.hpp"
#include "tellus/formats/stacks/stack_edit.hpp"

namespace tellus {

struct StackLevel {
  QuantisedStacks stacks;  // in the pipeline's sample order (x east, y north)
  // Per sample column (x + width * y): the lowest layer boundary above the terrain's base and
  // the highest top of every finest-level column under it, metres (lowest > highest: empty).
  // Aggregation only moves boundaries between those of the columns it merges, so no level
  // has a surface in a column outside this range, but for the floor at the base.
  std::vector<float> lowestBoundaryM, highestTopM;
  // Per sample column, levels above 0 (empty at level 0): how far, vertically, this column's
  // surfaces lie from those of the finer columns under it (stack_level_error.hpp; the largest
  // of this level's against the level below and the error that level already has: an
  // estimate of the error against the finest level, not a bound), and the heights where the mismatches larger than half a cell lie
  // (errorLowM > errorHighM: none). The octree refines where this error is large on screen.
  std::vector<float> errorM, errorLowM, errorHighM;
};

class StackLevels {
 public:
  // `pyramid`: level 0 first, each level half the one before (buildStackPyramid, a .tstack).
  // cellM: density cell height of level 0 (> 0). Quantises every level (all cores).
  static Result<StackLevels> build(const std::vector<StackTerrain>& pyramid, double cellM,
                                   const QuadParams& params);

  // After an edit (stacks/stack_edit.hpp): every level of `pyramid` whose region in `changed`
  // (one per level, updatePyramid's) is not empty quantised again, and the height ranges.
  Status rebuild(const std::vector<StackTerrain>& pyramid, const std::vector<StackRegion>& changed);

  int count() const { return int(levels_.size()); }
  const StackLevel& level(int k) const { return levels_[std::size_t(k)]; }
  const QuadParams& params() const { return params_; }
  double cellM() const { return cellM_; }            // level 0's density cell height
  double spacingM() const { return spacingM_; }      // level 0's stack spacing
  float topM() const { return topM_; }               // the highest layer top
  int width() const { return levels_.front().stacks.width; }
  int height() const { return levels_.front().stacks.height; }

  // The world base of level k's cells: -(2^k - 1) / 2 * cellM.
  static double levelBaseM(int k, double cellM);

 private:
  // Quantises every level (`changed` empty) or, after an edit, the region of each level in
  // `changed` (one per level, terrain rows; empty regions untouched), and the height ranges.
  Status quantise(const std::vector<StackTerrain>& pyramid, const std::vector<StackRegion>& changed);
  // The geometric errors of every level above 0 over `changed` (one region per level, terrain
  // rows; all columns when empty), finest level first (each builds on the one below).
  void computeErrors(const std::vector<StackTerrain>& pyramid, const std::vector<StackRegion>& changed);

  std::vector<StackLevel> levels_;
  QuadParams params_;
  double cellM_ = 1.0, spacingM_ = 1.0;
  float topM_ = 0.0f;
};

}  // namespace tellus
