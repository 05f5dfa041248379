#pragma once
// How far a coarse stack column's surfaces lie from a finer column's (the octree's geometric
// error, beyond the seed). GL-free.
//
// The seed refines the octree by the screen size of a cell alone, which keeps a smooth hill
// right but loses thin features: a cave roof thinner than a coarse cell aggregates to air (the
// sky shows through it from inside the cave) and a narrow passage to rock. The vertical
// Hausdorff distance between the two columns' surfaces (the heights where solid meets air)
// measures that: a vanished roof of a cave h metres high is an error of about h, a slope
// shifted by aggregation an error of a fraction of a cell.
#include <limits>
#include <span>

#include "tellus/formats/stacks/material_stack.hpp"

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

// The surfaces of `coarse` against those of `fine`: the largest distance from a surface of
// either column to the nearest surface of the other (a column with no layer has the base, 0,
// as its only surface). Mismatches above `toleranceM` extend the range.
ColumnError columnSurfaceError(std::span<const StackLayer> coarse, std::span<const StackLayer> fine,
                               float toleranceM);

}  // namespace tellus
