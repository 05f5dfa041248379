#include "support/stack_fixtures.hpp"

#include <cmath>

#include "tellus/dem/height_grid.hpp"
#include "tellus/formats/stacks/stack_generator.hpp"

namespace tellus::test {

Result<StackTerrain> hillsWithCaves(const HillsWithCaves& shape) {
  HeightGrid grid(shape.width, shape.height);
  for (int y = 0; y < grid.height; ++y) {
    for (int x = 0; x < grid.width; ++x) {
      grid.at(x, y) = float(shape.amplitudeM * std::sin(x * shape.waveX) * std::cos(y * shape.waveY) +
                            shape.riseM * x);
    }
  }
  grid.spacingXM = grid.spacingYM = shape.spacingM;
  StackGeneratorOptions options;
  if (shape.caveScaleM > 0.0) options.caveScaleM = shape.caveScaleM;
  return generateStacks(grid, options);
}

}  // namespace tellus::test
