#include "tellus/formats/stacks/stack_surface.hpp"

namespace tellus {

HeightGrid topSurfaceGrid(const StackTerrain& stacks) {
  HeightGrid grid(stacks.width(), stacks.height());
  grid.spacingXM = grid.spacingYM = stacks.spacingM();
  for (int y = 0; y < stacks.height(); ++y) {
    for (int x = 0; x < stacks.width(); ++x) {
      const auto column = stacks.column(x, y);
      grid.at(x, y) = column.empty() ? 0.0f : column.back().topM;
    }
  }
  return grid;
}

Aabb stackWorldBounds(const StackTerrain& stacks) {
  Aabb box;
  box.min = glm::dvec3(0.0);
  box.max = glm::dvec3(double(stacks.width() - 1) * stacks.spacingM(),
                       double(stacks.height() - 1) * stacks.spacingM(), double(stacks.topM()));
  return box;
}

}  // namespace tellus
