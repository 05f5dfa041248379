#include "tellus/formats/stacks/material_stack.hpp"

#include "tellus/formats/stacks/column_splice.hpp"

#include <algorithm>
#include <cmath>

namespace tellus {

Status checkStackColumn(std::span<const StackLayer> column) {
  for (std::size_t i = 0; i < column.size(); ++i) {
    const StackLayer& l = column[i];
    if (!std::isfinite(l.bottomM) || !std::isfinite(l.topM)) {
      return makeError("layer {}: heights must be finite", i);
    }
    if (l.material == kAir) return makeError("layer {}: air is the gap between layers, not a layer", i);
    if (!(l.topM > l.bottomM)) {
      return makeError("layer {}: its top {} m is not above its bottom {} m", i, l.topM, l.bottomM);
    }
    if (i > 0 && l.bottomM < column[i - 1].topM) {
      return makeError("layer {} starts at {} m, below the top of the layer under it ({} m)", i,
                       l.bottomM, column[i - 1].topM);
    }
  }
  return {};
}

Result<StackTerrain> StackTerrain::fromColumns(int width, int height, double spacingM,
                                               const std::vector<std::vector<StackLayer>>& columns) {
  if (width < 1 || height < 1 || std::size_t(width) * std::size_t(height) != columns.size()) {
    return makeError("stacks: {} columns for a {} x {} grid", columns.size(), width, height);
  }
  std::vector<std::uint32_t> offsets{0};
  std::vector<StackLayer> layers;
  for (const std::vector<StackLayer>& column : columns) {
    layers.insert(layers.end(), column.begin(), column.end());
    if (layers.size() > 0xffffffffu) return makeError("stacks: more than 2^32 layers");
    offsets.push_back(std::uint32_t(layers.size()));
  }
  return fromArrays(width, height, spacingM, std::move(offsets), std::move(layers));
}

Result<StackTerrain> StackTerrain::fromArrays(int width, int height, double spacingM,
                                              std::vector<std::uint32_t> offsets,
                                              std::vector<StackLayer> layers) {
  if (width < 1 || height < 1 || width > (1 << 20) || height > (1 << 20)) {
    return makeError("stacks: a grid of {} x {} stacks", width, height);
  }
  if (!(spacingM > 0.0) || !std::isfinite(spacingM)) {
    return makeError("stacks: the spacing must be positive metres, got {}", spacingM);
  }
  const std::size_t count = std::size_t(width) * std::size_t(height);
  if (offsets.size() != count + 1 || offsets.front() != 0 || offsets.back() != layers.size()) {
    return makeError("stacks: column offsets do not match the {} columns and {} layers", count,
                     layers.size());
  }
  for (std::size_t c = 0; c < count; ++c) {
    if (offsets[c + 1] < offsets[c]) return makeError("stacks: column {} ends before it starts", c);
    if (offsets[c + 1] > layers.size()) return makeError("stacks: column {} ends beyond the layers", c);
    const std::span<const StackLayer> column(layers.data() + offsets[c], offsets[c + 1] - offsets[c]);
    if (Status s = checkStackColumn(column); !s) {
      return makeError("stacks: column ({}, {}): {}", c % std::size_t(width), c / std::size_t(width),
                       s.error().message);
    }
  }
  StackTerrain t;
  t.width_ = width;
  t.height_ = height;
  t.spacingM_ = spacingM;
  t.offsets_ = std::move(offsets);
  t.layers_ = std::move(layers);
  return t;
}

Status StackTerrain::replaceColumns(const StackRegion& region,
                                    const std::vector<std::vector<StackLayer>>& columns) {
  if (region.empty() || region.x0 < 0 || region.y0 < 0 || region.x1 >= width_ ||
      region.y1 >= height_) {
    return makeError("stacks: region x {}..{}, rows {}..{} is not inside the {} x {} grid",
                     region.x0, region.x1, region.y0, region.y1, width_, height_);
  }
  const std::size_t regionWidth = std::size_t(region.x1 - region.x0 + 1);
  if (columns.size() != regionWidth * std::size_t(region.y1 - region.y0 + 1)) {
    return makeError("stacks: {} columns for a region of {} x {}", columns.size(), regionWidth,
                     region.y1 - region.y0 + 1);
  }
  std::size_t removed = 0, added = 0;
  std::vector<ColumnRun<StackLayer>> runs;
  for (int row = region.y0; row <= region.y1; ++row) {
    ColumnRun<StackLayer>& run = runs.emplace_back();
    run.firstColumn = std::size_t(row) * std::size_t(width_) + std::size_t(region.x0);
    removed += offsets_[run.firstColumn + regionWidth] - offsets_[run.firstColumn];
    for (std::size_t i = 0; i < regionWidth; ++i) {
      const std::vector<StackLayer>& column = columns[std::size_t(row - region.y0) * regionWidth + i];
      if (Status s = checkStackColumn(column); !s) {
        return makeError("stacks: column ({}, {}): {}", region.x0 + int(i), row, s.error().message);
      }
      run.counts.push_back(std::uint32_t(column.size()));
      run.layers.insert(run.layers.end(), column.begin(), column.end());
      added += column.size();
    }
  }
  if (layers_.size() - removed + added > 0xffffffffu) return makeError("stacks: more than 2^32 layers");
  spliceColumns(layers_, offsets_, runs);
  return {};
}

std::span<const StackLayer> StackTerrain::column(int x, int y) const {
  const std::size_t c = std::size_t(y) * std::size_t(width_) + std::size_t(x);
  return {layers_.data() + offsets_[c], offsets_[c + 1] - offsets_[c]};
}

float StackTerrain::topM() const {
  float top = 0.0f;
  for (const StackLayer& l : layers_) top = std::max(top, l.topM);
  return top;
}

std::uint64_t StackTerrain::bytes() const {
  return layers_.size() * sizeof(StackLayer) + offsets_.size() * sizeof(std::uint32_t);
}

std::uint64_t StackTerrain::denseVoxelBytes(double cellM) const {
  const auto levels = std::uint64_t(std::ceil(double(topM()) / cellM));
  return std::uint64_t(width_) * std::uint64_t(height_) * levels;
}

}  // namespace tellus
