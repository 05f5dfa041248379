#pragma once
// A stack terrain seen as a heightfield where that is all a caller needs: the top of each
// column (camera placement, named views, camera paths that follow the ground), and its bounds
// in the world frame the stack renderers draw in. GL-free.
#include "tellus/core/aabb.hpp"
#include "tellus/dem/height_grid.hpp"
#include "tellus/formats/stacks/material_stack.hpp"

namespace tellus {

// The highest layer top of every column (0 where a column is empty), same grid and spacing,
// row 0 north.
HeightGrid topSurfaceGrid(const StackTerrain& stacks);

// x east and y north of the south-west stack (0 .. (size - 1) * spacing), z from the base (0) to
// the highest top.
Aabb stackWorldBounds(const StackTerrain& stacks);

}  // namespace tellus
