#pragma once
// Heights for RINGO's tests: a block's samples as a function of their depth-D sample positions
// (as the store's nested tiles give them), so that every level of a block samples the same
// surface; pseudo-random in [base, base + spread) metres, rough enough that a misplaced vertex
// is metres off.
#include <cstdint>
#include <vector>

#include "tellus/lod/ringo/ringo_block_matrix.hpp"

namespace tellus::test {

inline std::vector<float> ringoTestHeights(const RingoBlock& block, const RingoLayout& layout,
                                           double base, int spread) {
  const int cells = layout.cellsAt(block.level), stride = 1 << block.level;
  std::vector<float> heights;
  for (int j = 0; j <= cells; ++j) {
    for (int i = 0; i <= cells; ++i) {
      const std::int64_t x = std::int64_t(block.key.x) * layout.tileCells + i * stride;
      const std::int64_t y = std::int64_t(block.key.y) * layout.tileCells + j * stride;
      heights.push_back(float(base + double((x * 7919 + y * 104729) % spread)));
    }
  }
  return heights;
}

}  // namespace tellus::test
