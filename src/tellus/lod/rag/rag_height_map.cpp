#include "tellus/lod/rag/rag_height_map.hpp"

#include <algorithm>
#include <cmath>

#include <tbb/blocked_range.h>
#include <tbb/parallel_reduce.h>

namespace tellus::rag {
namespace {

int levelSide(int side, int level) { return (side - 1) / (1 << level) + 1; }

}  // namespace

int heightMapLevel(int width, int height, int maxSide) {
  int level = 0;
  while ((levelSide(width, level) > maxSide || levelSide(height, level) > maxSide) &&
         levelSide(width, level) > 2 && levelSide(height, level) > 2) {
    ++level;
  }
  return level;
}

HeightMap heightMapAtLevel(const HeightGrid& full, int level) {
  HeightMap map;
  map.level = level;
  const int step = 1 << level;
  HeightGrid& grid = map.grid;
  grid = HeightGrid(levelSide(full.width, level), levelSide(full.height, level));
  grid.spacingXM = full.spacingXM * step;
  grid.spacingYM = full.spacingYM * step;
  grid.georef = full.georef;
  map.droppedColumns = full.width - 1 - (grid.width - 1) * step;
  map.droppedRows = full.height - 1 - (grid.height - 1) * step;
  // Row r of the level (0 north) is input row rowOffset + r * step: the southern rows coincide.
  const int rowOffset = map.droppedRows;
  for (int r = 0; r < grid.height; ++r) {
    for (int c = 0; c < grid.width; ++c) grid.at(c, r) = full.at(c * step, rowOffset + r * step);
  }
  if (level == 0) return map;
  // The error: every covered input sample against the level interpolated at its position.
  map.errorM = tbb::parallel_reduce(
      tbb::blocked_range<int>(rowOffset, full.height), 0.0f,
      [&](const tbb::blocked_range<int>& rows, float worst) {
        for (int row = rows.begin(); row != rows.end(); ++row) {
          const double y = (full.height - 1 - row) * full.spacingYM;
          for (int col = 0; col <= (grid.width - 1) * step; ++col) {
            const float interpolated = grid.heightAtWorld(col * full.spacingXM, y);
            worst = std::max(worst, std::abs(full.at(col, row) - interpolated));
          }
        }
        return worst;
      },
      [](float a, float b) { return std::max(a, b); });
  return map;
}

}  // namespace tellus::rag
