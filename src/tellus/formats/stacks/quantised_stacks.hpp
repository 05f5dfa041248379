#pragma once
// Material stacks in the units of the quadrangulation pipeline (seed 003, section 3.2): layer
// heights as integers of 1/kSubCell of a density cell above the terrain's base, so the CPU
// reference and the compute shaders rasterise exactly the same coverage (integer arithmetic,
// no rounding left to either side). GL-free.
//
// Grid convention of the pipeline: sample (x, y) is stack column x and row height - 1 - y, so
// x runs east, y north and z up (right-handed, like world space); sample z is density cell z
// above the base, cells of cellM metres.
#include <cstdint>
#include <span>
#include <vector>

#include "tellus/formats/stacks/material_stack.hpp"

namespace tellus {

inline constexpr std::int32_t kSubCell = 256;     // coverage units per density cell
inline constexpr int kMaterialChannels = 4;       // density channels: materials 1, 2, 3, 4+

// Density channel of a solid material: 1 -> 0, 2 -> 1, 3 -> 2, 4 and above -> 3.
constexpr int materialChannel(StackMaterial material) {
  return material >= kMaterialChannels ? kMaterialChannels - 1 : int(material) - 1;
}

struct QuantisedLayer {
  std::int32_t bottom = 0;  // 1/kSubCell of a cell above the base
  std::int32_t top = 0;     // > bottom
  std::uint32_t channel = 0;  // materialChannel() of the layer's material
  std::uint32_t padding = 0;  // keeps the GPU copy 16-byte aligned (std430 ivec4)
};

struct QuantisedStacks {
  int width = 0, height = 0;  // stacks
  int cellsZ = 0;             // density cells up to the highest layer top (rounded up)
  double spacingM = 1.0;      // between stacks
  double cellM = 1.0;         // vertical size of a density cell
  // World height (metres above the terrain's base) of the bottom of density cell 0: 0 for the
  // finest level; a coarser level of the octree (lod/stacks) shifts its cells so that its
  // samples fall on samples of the finest level (see StackLevels).
  double baseM = 0.0;
  int level = 0;  // its level in the stack MipMap (the vertices' position.w)
  std::vector<std::uint32_t> offsets;  // column c = x + width * y: [offsets[c], offsets[c + 1])
  std::vector<QuantisedLayer> layers;

  // Layers rounded to the nearest 1/kSubCell of `cellM` (layers thinner than that vanish).
  // Materials are seen at the resolution of the cells: in each solid interval of a column the
  // layer at its top (and at its bottom, over air) is made at least one cell thick at the
  // expense of the layers it touches, so thin surface layers (grass) colour the surface; what
  // each interval covers, the geometry, is unchanged.
  // Heights are measured from baseM (<= 0: cells below the base are air). cellM > 0; heights
  // must fit ((topM - baseM) / cellM * kSubCell < 2^30), else an error.
  static Result<QuantisedStacks> from(const StackTerrain& terrain, double cellM,
                                      double baseM = 0.0);

  // The layers of grid sample (x, y) (y north), empty outside the terrain.
  std::span<const QuantisedLayer> column(int x, int y) const;

  // After an edit of `terrain` (the stacks these were made from, same size) within `region`
  // (terrain rows, row 0 north): those columns quantised again, the others' layers moved as
  // blocks; equal to from(terrain, cellM, baseM). Errors (a region outside, a terrain too
  // high for the cells) leave the stacks unchanged.
  Status replaceRegion(const StackTerrain& terrain, const StackRegion& region);

 private:
  void updateCellsZ();  // from the highest layer top
};

}  // namespace tellus
