#pragma once
// Stacks to density (seed 003, section 3.2.1), the CPU reference: a column's layers rasterised
// into a column of cells like a line, each cell's density the fraction of it the layers cover
// (air counts nothing). GL-free.
#include <span>

#include "tellus/stacks/material_stack.hpp"

namespace tellus {

// Adds the coverage of `column`'s layers (all of them, or only those of `material` when it is
// not air) to `density`, whose cell k spans [originM + k cellM, originM + (k + 1) cellM). In
// cell units s and e (a layer's bottom and top): the first covered cell floor(s) gets
// 1 - frac(s), the last floor(e) gets frac(e), those between 1, and a layer inside one cell
// gets e - s; cells covered by several layers add them up. Layers are clipped to the cells.
void addColumnDensity(std::span<const StackLayer> column, double originM, double cellM,
                      std::span<float> density, StackMaterial material = kAir);

}  // namespace tellus
