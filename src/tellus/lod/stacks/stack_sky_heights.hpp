#pragma once
// Where a stack terrain meets the sky: per column, the top of its highest layer, the surface an
// orthophoto shows. Imagery draped on stack terrain (render/stacks/stack_sky_texture.hpp) colours
// only the surfaces at that top, not cave floors, the ground under an overhang or arch, or
// cliff walls. GL-free.
#include <cstdint>
#include <vector>

#include "tellus/formats/stacks/material_stack.hpp"

namespace tellus {

// Column tops quantised to 16 bits, `factor` x `factor` finest columns to a value (the highest
// of them), in the pipeline's sample order: value (i, j) covers columns i * factor .. and sample
// rows j * factor .. counted from the south (terrain row height - 1 - j * factor, northwards).
struct StackSkyHeights {
  int width = 0, height = 0;      // values
  int factor = 1;                 // finest columns a value spans, each way (a power of two)
  double spacingM = 1.0;          // between the finest columns, metres
  double scaleM = 1.0;            // metres a quantum: top = value * scaleM (rounded up)
  std::vector<std::uint16_t> values;  // width * height, row j = sample rows from the south
};

// The tops of `finest` (a .tstack's level 0), reduced until at most `maxValues` values remain
// (a 4801^2 terrain fits 2^24 at factor 2). A column without layers has top 0. Quantised
// upwards, so no value is below its columns' tops.
StackSkyHeights stackSkyHeights(const StackTerrain& finest, std::uint64_t maxValues = std::uint64_t(1) << 24);

}  // namespace tellus
