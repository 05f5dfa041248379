#include "tellus/stacks/quantised_stacks.hpp"

#include <cmath>

namespace tellus {
namespace {

// Within each run of touching layers of a column (one solid interval), the layer at its top is
// made at least one cell thick, and so is the layer at its bottom when air lies under it (a
// ceiling), by moving the boundaries between the run's layers: what the interval covers, and so
// the geometry, is unchanged; only which material a surface cell reports changes, so that a
// surface shows its own material (grass 0.25 m thick over soil, in cells of 2 m) instead of
// what lies under it. The top has the last word where a run is thinner than two cells.
void thickenSurfaceMaterials(std::vector<QuantisedLayer>& layers, std::size_t first,
                             std::int32_t floorUnits) {
  std::vector<QuantisedLayer> out;
  const auto append = [&](std::int32_t bottom, std::int32_t top, std::uint32_t channel) {
    if (top <= bottom) return;
    if (!out.empty() && out.back().top == bottom && out.back().channel == channel) {
      out.back().top = top;  // same material continues
    } else {
      out.push_back({bottom, top, channel, 0});
    }
  };
  std::size_t begin = first;
  for (std::size_t end = first + 1; end <= layers.size(); ++end) {
    if (end < layers.size() && layers[end].bottom == layers[end - 1].top) continue;
    // [begin, end): one run of touching layers.
    const std::int32_t runBottom = layers[begin].bottom, runTop = layers[end - 1].top;
    const std::int32_t topZone = std::max(runTop - kSubCell, runBottom);
    const std::int32_t bottomZone = runBottom > floorUnits ? std::min(runBottom + kSubCell, topZone) : runBottom;
    append(runBottom, bottomZone, layers[begin].channel);  // a ceiling's own material
    for (std::size_t i = begin; i < end; ++i) {
      append(std::max(layers[i].bottom, bottomZone), std::min(layers[i].top, topZone),
             layers[i].channel);
    }
    append(topZone, runTop, layers[end - 1].channel);  // the surface's own material
    begin = end;
  }
  layers.resize(first);
  layers.insert(layers.end(), out.begin(), out.end());
}

}  // namespace

Result<QuantisedStacks> QuantisedStacks::from(const StackTerrain& terrain, double cellM,
                                              double baseM) {
  if (!(cellM > 0.0) || !std::isfinite(cellM)) {
    return makeError("density cell size must be positive (got {} m)", cellM);
  }
  if (!(baseM <= 0.0) || !std::isfinite(baseM)) {
    return makeError("density cell base must be at or below the terrain's base (got {} m)", baseM);
  }
  const double limit = double(1 << 30);
  if ((double(terrain.topM()) - baseM) / cellM * kSubCell >= limit) {
    return makeError("terrain top {} m is too high for density cells of {} m", terrain.topM(),
                     cellM);
  }
  QuantisedStacks out;
  out.width = terrain.width();
  out.height = terrain.height();
  out.spacingM = terrain.spacingM();
  out.cellM = cellM;
  out.baseM = baseM;
  out.offsets.reserve(std::size_t(out.width) * std::size_t(out.height) + 1);
  out.layers.reserve(terrain.layerCount());
  std::int32_t highest = 0;
  const auto quantise = [&](float metres) {
    return std::int32_t(std::llround((double(metres) - baseM) / cellM * kSubCell));
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
      thickenSurfaceMaterials(out.layers, out.offsets.back(), quantise(0.0f));
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
