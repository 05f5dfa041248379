#pragma once
// How far a coarse stack column's surfaces lie from a finer column's (the octree's geometric
// error, beyond the seed). GL-free.
//
// The seed refines the octree by the screen size of a cell alone, which keeps a smooth hill
// right but loses thin features: a cave roof thinner than a coarse cell aggregates to air (the
// sky shows through it from inside the cave) and a narrow passage to rock. The vertical
// Hausdorff distance between the two columns' surfaces (the heights where solid meets air)
// measures that: a vanished roof of a cave h metres high is an error of about h, a slope
// shifted by aggregation an error of a fraction of a cell. The smoothing before dual
// contouring loses more: a solid run thinner than about a cell of its level is smoothed below
// the iso-value and vanishes from the mesh (a thin terrain's whole slab, seen from afar), an air
// gap as thin fills in. Each column's surfaces are therefore those its level's mesh can show:
// runs and gaps thinner than survivingRunCells() cells of that level are left out.
#include <limits>
#include <span>

#include "tellus/formats/stacks/material_stack.hpp"
#include "tellus/formats/stacks/quadrangulation.hpp"

namespace tellus {

struct ColumnError {
  float errorM = 0.0f;  // vertical Hausdorff distance between the two columns' surfaces, metres
  // The heights spanned by the mismatches larger than the tolerance (each surface and the
  // nearest surface of the other column): where the error is; empty (low > high) when none.
  float lowM = std::numeric_limits<float>::max();
  float highM = std::numeric_limits<float>::lowest();
  bool hasRange() const { return lowM <= highM; }
  // The larger error, and the union of the ranges.
  void include(const ColumnError& other);
};

// The error of a coarse column that has layers but whose every run the smoothing loses, while
// the finer column shows a surface: a hole at any distance, so the node is always split.
inline constexpr float kVanishedErrorM = 1e9f;

// The thinnest solid run (or air gap), in density cells, whose surfaces the smoothing of
// `params` keeps at every alignment to the cells (some sample's smoothed density crosses the
// iso-value): 1.33 cells for the default Gauss 1 2 1, just over 1 without smoothing, 2.5 for
// five equal taps.
double survivingRunCells(const QuadParams& params);

// The surfaces of `coarse` against those of `fine`: the largest distance from a surface of
// either column to the nearest surface of the other (a column with no surface left has the
// base, 0, as its only surface). Air gaps thinner than a column's minRunM are filled and solid
// runs thinner than it left out first (0: every run counts); a coarse column with layers and
// no surface left against a finer one with some is kVanishedErrorM over the finer one's
// heights. Mismatches above `toleranceM` extend the range.
ColumnError columnSurfaceError(std::span<const StackLayer> coarse, std::span<const StackLayer> fine,
                               float toleranceM, float coarseMinRunM = 0.0f,
                               float fineMinRunM = 0.0f);

}  // namespace tellus
