#pragma once
// Material stacks (seed 003, after Benes and Forsbach and Peytavie et al.): terrain with arches,
// overhangs and caves as a 2D grid of columns, each column a run-length list of material layers
// from the bottom up; the gaps between layers are air. GL-free.
//
// Units: heights in metres above the terrain's base (0), x and y in stacks (spacingM metres
// apart), row 0 north like HeightGrid. Material 0 is air and never stored as a layer.
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "tellus/core/result.hpp"

namespace tellus {

using StackMaterial = std::uint8_t;
inline constexpr StackMaterial kAir = 0;

struct StackLayer {
  float bottomM = 0.0f;  // where the layer starts, metres
  float topM = 0.0f;     // where it ends (> bottomM)
  StackMaterial material = kAir;
  bool operator==(const StackLayer&) const = default;
};

// A column is valid when its layers are solid (material != air), each of positive thickness,
// bottom to top without overlapping (a layer may start where the one below ends), and finite.
// Errors say which layer and why.
Status checkStackColumn(std::span<const StackLayer> column);

// Columns x0..x1, rows y0..y1 (row 0 north), inclusive, at one level; empty when x0 > x1.
struct StackRegion {
  int x0 = 0, y0 = 0, x1 = -1, y1 = -1;
  bool empty() const { return x0 > x1 || y0 > y1; }
};

class StackTerrain {
 public:
  StackTerrain() = default;
  // `columns` row by row (width * height of them), each checked by checkStackColumn.
  static Result<StackTerrain> fromColumns(int width, int height, double spacingM,
                                          const std::vector<std::vector<StackLayer>>& columns);

  int width() const { return width_; }
  int height() const { return height_; }
  double spacingM() const { return spacingM_; }
  std::span<const StackLayer> column(int x, int y) const;
  std::size_t layerCount() const { return layers_.size(); }
  float topM() const;  // the highest layer top (0 for an empty terrain)

  // Replaces the columns of `region` (inside the grid, not empty) with `columns`, row by row
  // (its width * height of them, each checked by checkStackColumn). One pass over the arrays:
  // the other columns' layers are moved as blocks (an edit, not a rebuild). Errors leave the
  // terrain unchanged.
  Status replaceColumns(const StackRegion& region,
                        const std::vector<std::vector<StackLayer>>& columns);

  // Memory held: the layers and the column offsets.
  std::uint64_t bytes() const;
  // The same terrain as a dense voxel grid of one byte a voxel (a material id), cells of
  // `cellM` metres up to topM(): what stacks save.
  std::uint64_t denseVoxelBytes(double cellM) const;

  // The raw arrays (file writers): offsets has width * height + 1 entries.
  const std::vector<std::uint32_t>& offsets() const { return offsets_; }
  const std::vector<StackLayer>& layers() const { return layers_; }
  // From raw arrays, checked (file readers never trust them).
  static Result<StackTerrain> fromArrays(int width, int height, double spacingM,
                                         std::vector<std::uint32_t> offsets,
                                         std::vector<StackLayer> layers);

 private:
  int width_ = 0, height_ = 0;
  double spacingM_ = 1.0;
  std::vector<std::uint32_t> offsets_;  // column c's layers: [offsets_[c], offsets_[c + 1])
  std::vector<StackLayer> layers_;
};

}  // namespace tellus
