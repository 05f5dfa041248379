#include "tellus/formats/stacks/quantised_stacks.hpp"

#include "tellus/formats/stacks/column_splice.hpp"

#include <algorithm>
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

// Quantises `column` onto the end of `layers` (QuantisedStacks::from()'s rules).
void appendQuantisedColumn(std::span<const StackLayer> column, double cellM, double baseM,
                           std::vector<QuantisedLayer>& layers) {
  const std::size_t first = layers.size();
  const auto quantise = [&](float metres) {
    return std::int32_t(std::llround((double(metres) - baseM) / cellM * kSubCell));
  };
  for (const StackLayer& layer : column) {
    QuantisedLayer q;
    q.bottom = quantise(layer.bottomM);
    q.top = quantise(layer.topM);
    q.channel = std::uint32_t(materialChannel(layer.material));
    if (q.top <= q.bottom) continue;
    // Neighbouring layers round their shared boundary alike; a layer that rounds below
    // the previous top (only when thinner than a unit) is clipped to it.
    if (layers.size() > first && q.bottom < layers.back().top) {
      q.bottom = layers.back().top;
      if (q.top <= q.bottom) continue;
    }
    layers.push_back(q);
  }
  thickenSurfaceMaterials(layers, first, quantise(0.0f));
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
  for (int y = 0; y < out.height; ++y) {
    const int row = out.height - 1 - y;  // sample y runs north
    for (int x = 0; x < out.width; ++x) {
      out.offsets.push_back(std::uint32_t(out.layers.size()));
      appendQuantisedColumn(terrain.column(x, row), cellM, baseM, out.layers);
    }
  }
  out.offsets.push_back(std::uint32_t(out.layers.size()));
  out.updateCellsZ();
  return out;
}

void QuantisedStacks::updateCellsZ() {
  std::int32_t highest = 0;
  for (const QuantisedLayer& layer : layers) highest = std::max(highest, layer.top);
  cellsZ = int((highest + kSubCell - 1) / kSubCell);
}

Status QuantisedStacks::replaceRegion(const StackTerrain& terrain, const StackRegion& region) {
  if (terrain.width() != width || terrain.height() != height) {
    return makeError("quantised stacks of {} x {} cannot take columns of a {} x {} terrain", width,
                     height, terrain.width(), terrain.height());
  }
  if (region.empty() || region.x0 < 0 || region.y0 < 0 || region.x1 >= width || region.y1 >= height) {
    return makeError("region x {}..{}, rows {}..{} is not inside the {} x {} stacks", region.x0,
                     region.x1, region.y0, region.y1, width, height);
  }
  // Only the region's columns are new: the others fitted the cells when they were quantised.
  float regionTopM = 0.0f;
  for (int row = region.y0; row <= region.y1; ++row) {
    for (int x = region.x0; x <= region.x1; ++x) {
      for (const StackLayer& layer : terrain.column(x, row)) regionTopM = std::max(regionTopM, layer.topM);
    }
  }
  if ((double(regionTopM) - baseM) / cellM * kSubCell >= double(1 << 30)) {
    return makeError("terrain top {} m is too high for density cells of {} m", regionTopM, cellM);
  }
  // Sample rows (y north) of the region's terrain rows, in storage order.
  const int y0 = height - 1 - region.y1, y1 = height - 1 - region.y0;
  std::vector<ColumnRun<QuantisedLayer>> runs;
  for (int y = y0; y <= y1; ++y) {
    ColumnRun<QuantisedLayer>& run = runs.emplace_back();
    run.firstColumn = std::size_t(y) * std::size_t(width) + std::size_t(region.x0);
    for (int x = region.x0; x <= region.x1; ++x) {
      const std::size_t before = run.layers.size();
      appendQuantisedColumn(terrain.column(x, height - 1 - y), cellM, baseM, run.layers);
      run.counts.push_back(std::uint32_t(run.layers.size() - before));
    }
  }
  spliceColumns(layers, offsets, runs);
  updateCellsZ();
  return {};
}

std::span<const QuantisedLayer> QuantisedStacks::column(int x, int y) const {
  if (x < 0 || y < 0 || x >= width || y >= height) return {};
  const std::size_t c = std::size_t(x) + std::size_t(width) * std::size_t(y);
  return std::span<const QuantisedLayer>(layers).subspan(offsets[c], offsets[c + 1] - offsets[c]);
}

}  // namespace tellus
