#include "tellus/stacks/quantised_stacks.hpp"

#include <cmath>

namespace tellus {

Result<QuantisedStacks> QuantisedStacks::from(const StackTerrain& terrain, double cellM) {
  if (!(cellM > 0.0) || !std::isfinite(cellM)) {
    return makeError("density cell size must be positive (got {} m)", cellM);
  }
  const double limit = double(1 << 30);
  if (double(terrain.topM()) / cellM * kSubCell >= limit) {
    return makeError("terrain top {} m is too high for density cells of {} m", terrain.topM(),
                     cellM);
  }
  QuantisedStacks out;
  out.width = terrain.width();
  out.height = terrain.height();
  out.spacingM = terrain.spacingM();
  out.cellM = cellM;
  out.offsets.reserve(std::size_t(out.width) * std::size_t(out.height) + 1);
  out.layers.reserve(terrain.layerCount());
  std::int32_t highest = 0;
  const auto quantise = [&](float metres) {
    return std::int32_t(std::llround(double(metres) / cellM * kSubCell));
  };
  for (int y = 0; y < out.height; ++y) {
    const int row = out.height - 1 - y;  // sample y runs north
    for (int x = 0; x < out.width; ++x) {
      out.offsets.push_back(std::uint32_t(out.layers.size()));
      for (const StackLayer& layer : terrain.column(x, row)) {
        QuantisedLayer q;
        q.bottom = quantise(layer.bottomM);
        q.top = quantise(layer.topM);
        q.channel = std::uint32_t(materialChannel(layer.material));
        if (q.top <= q.bottom) continue;
        // Neighbouring layers round their shared boundary alike; a layer that rounds below
        // the previous top (only when thinner than a unit) is clipped to it.
        if (!out.layers.empty() && out.offsets.back() < out.layers.size() &&
            q.bottom < out.layers.back().top) {
          q.bottom = out.layers.back().top;
          if (q.top <= q.bottom) continue;
        }
        highest = std::max(highest, q.top);
        out.layers.push_back(q);
      }
    }
  }
  out.offsets.push_back(std::uint32_t(out.layers.size()));
  out.cellsZ = int((highest + kSubCell - 1) / kSubCell);
  return out;
}

std::span<const QuantisedLayer> QuantisedStacks::column(int x, int y) const {
  if (x < 0 || y < 0 || x >= width || y >= height) return {};
  const std::size_t c = std::size_t(x) + std::size_t(width) * std::size_t(y);
  return std::span<const QuantisedLayer>(layers).subspan(offsets[c], offsets[c + 1] - offsets[c]);
}

}  // namespace tellus
