#include "tellus/stacks/stack_density.hpp"

#include <algorithm>
#include <cmath>

namespace tellus {

void addColumnDensity(std::span<const StackLayer> column, double originM, double cellM,
                      std::span<float> density, StackMaterial material) {
  const double cells = double(density.size());
  for (const StackLayer& layer : column) {
    if (material != kAir && layer.material != material) continue;
    const double s = std::clamp((double(layer.bottomM) - originM) / cellM, 0.0, cells);
    const double e = std::clamp((double(layer.topM) - originM) / cellM, 0.0, cells);
    if (!(e > s)) continue;
    const double first = std::floor(s), last = std::floor(e);
    const auto at = [&](double k) -> float& { return density[std::size_t(k)]; };
    if (first == last) {
      at(first) += float(e - s);
      continue;
    }
    at(first) += float(1.0 - (s - first));
    for (double k = first + 1.0; k < last; k += 1.0) at(k) += 1.0f;
    if (last < cells) at(last) += float(e - last);
  }
}

}  // namespace tellus
