#include "tellus/lod/stacks/stack_sky_heights.hpp"

#include <algorithm>
#include <cmath>

#include <tbb/parallel_for.h>

namespace tellus {

StackSkyHeights stackSkyHeights(const StackTerrain& finest, std::uint64_t maxValues) {
  StackSkyHeights out;
  out.spacingM = finest.spacingM();
  while (std::uint64_t((finest.width() + out.factor - 1) / out.factor) *
             std::uint64_t((finest.height() + out.factor - 1) / out.factor) > std::max<std::uint64_t>(maxValues, 1)) {
    out.factor *= 2;
  }
  out.width = (finest.width() + out.factor - 1) / out.factor;
  out.height = (finest.height() + out.factor - 1) / out.factor;
  // The top's quantum: the terrain's top in 65,535 steps (0.14 m for 9 km).
  out.scaleM = std::max(double(finest.topM()), 1e-3) / 65535.0;
  out.values.assign(std::size_t(out.width) * std::size_t(out.height), 0);
  tbb::parallel_for(0, out.height, [&](int j) {
    for (int i = 0; i < out.width; ++i) {
      float top = 0.0f;
      for (int sy = j * out.factor; sy < std::min((j + 1) * out.factor, finest.height()); ++sy) {
        const int row = finest.height() - 1 - sy;  // sample rows run north, terrain rows south
        for (int x = i * out.factor; x < std::min((i + 1) * out.factor, finest.width()); ++x) {
          const std::span<const StackLayer> column = finest.column(x, row);
          if (!column.empty()) top = std::max(top, column.back().topM);
        }
      }
      const double quanta = std::ceil(double(top) / out.scaleM);
      out.values[std::size_t(j) * std::size_t(out.width) + std::size_t(i)] =
          std::uint16_t(std::clamp(quanta, 0.0, 65535.0));
    }
  });
  return out;
}

}  // namespace tellus
