#include "tellus/lod/stacks/seam_blend.hpp"

#include <algorithm>
#include <climits>

#include "tellus/lod/stacks/stack_octree.hpp"

namespace tellus {

std::uint32_t seamBits(std::uint32_t stitchMask, int keyX, int keyY, int keyZ) {
  // Keys may be negative (-1: the air around the terrain); & 1 is the child index in two's
  // complement, as OctreeKey::parent() floors.
  const std::uint32_t child = std::uint32_t(keyX & 1) | std::uint32_t(keyY & 1) << 1 |
                              std::uint32_t(keyZ & 1) << 2;
  return (stitchMask & ((1u << 27) - 1)) | child << 27;
}

float seamBlendWeight(std::array<int, 3> cell, std::uint32_t seam, int nodeCells, int bandCells) {
  const std::uint32_t mask = seam & ((1u << 27) - 1);
  if (bandCells <= 0 || mask == 0) return 0.0f;
  const int span = nodeCells - 1;  // cells from a node's first sample to the next node's
  // Node-local cells of the parent's first sample: the parent spans 2 span cells from there.
  std::array<int, 3> parentLow{};
  for (int a = 0; a < 3; ++a) parentLow[std::size_t(a)] = -int((seam >> (27 + a)) & 1u) * span;
  int nearest = INT_MAX;  // Chebyshev distance in cells to the nearest coarser neighbour
  for (int dz = -1; dz <= 1; ++dz) {
    for (int dy = -1; dy <= 1; ++dy) {
      for (int dx = -1; dx <= 1; ++dx) {
        if (!(mask & (1u << neighbourBit(dx, dy, dz)))) continue;
        const int d[3] = {dx, dy, dz};
        int distance = 0;
        for (int a = 0; a < 3; ++a) {
          const int low = parentLow[std::size_t(a)] + d[a] * 2 * span;
          const int high = low + 2 * span;
          const int c = cell[std::size_t(a)];
          distance = std::max(distance, std::max({0, low - c, c - high}));
        }
        nearest = std::min(nearest, distance);
      }
    }
  }
  if (nearest == INT_MAX) return 0.0f;
  const int band = std::min(bandCells, seamBandLimit(nodeCells));
  if (band <= 0) return 0.0f;
  // 1 at one cell, 0 from band + 1 cells: (band + 1 - distance) / band, clamped.
  const int steps = std::clamp(band + 1 - nearest, 0, band);
  return float(steps) / float(band);
}

float packMorphTargetCell(std::array<int, 3> cell, int nodeCells) {
  std::uint32_t bits = 0;
  for (int a = 0; a < 3; ++a) {
    const int c = cell[std::size_t(a)];
    if (c == 0) bits |= 1u << (2 * a);
    if (c == nodeCells - 1) bits |= 1u << (2 * a + 1);
    bits |= std::uint32_t(c & 63) << (6 + 6 * a);
  }
  return float(bits);
}

std::array<int, 3> morphTargetCell(const MorphTarget& target) {
  const auto bits = std::uint32_t(target[3] + 0.5f);
  return {int((bits >> 6) & 63u), int((bits >> 12) & 63u), int((bits >> 18) & 63u)};
}

unsigned morphTargetBorderBits(const MorphTarget& target) {
  return std::uint32_t(target[3] + 0.5f) & 63u;
}

std::array<float, 3> drawnStackVertexPosition(const std::array<float, 3>& own,
                                              const MorphTarget& target, float morphFactor,
                                              std::uint32_t unlikeNeighbours, std::uint32_t seam,
                                              int nodeCells, int bandCells) {
  // Pinned: a node sharing the vertex (the border bits say which offsets do) slides otherwise.
  const unsigned border = morphTargetBorderBits(target);
  int low[3], high[3];
  for (int a = 0; a < 3; ++a) {
    low[a] = (border & (1u << (2 * a))) ? -1 : 0;
    high[a] = (border & (1u << (2 * a + 1))) ? 1 : 0;
  }
  bool pinned = false;
  for (int dz = low[2]; dz <= high[2]; ++dz) {
    for (int dy = low[1]; dy <= high[1]; ++dy) {
      for (int dx = low[0]; dx <= high[0]; ++dx) {
        pinned = pinned || (unlikeNeighbours & (1u << neighbourBit(dx, dy, dz))) != 0;
      }
    }
  }
  const float slide = pinned ? 1.0f : morphFactor;
  const float weight = seamBlendWeight(morphTargetCell(target), seam, nodeCells, bandCells);
  const float keep = slide * (1.0f - weight);  // 1: its own position
  if (!(keep < 1.0f)) return own;
  std::array<float, 3> out{};
  for (int a = 0; a < 3; ++a) {
    out[std::size_t(a)] = target[std::size_t(a)] * (1.0f - keep) + own[std::size_t(a)] * keep;
  }
  return out;
}

}  // namespace tellus
