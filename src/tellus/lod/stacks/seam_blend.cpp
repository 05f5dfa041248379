#include "tellus/lod/stacks/seam_blend.hpp"

#include <algorithm>
#include <bit>
#include <climits>
#include <cmath>

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

float packMaterials(const std::array<float, 4>& weights) {
  std::uint32_t bits = 0;
  for (std::size_t m = 0; m < 4; ++m) {
    const float w = std::clamp(weights[m], 0.0f, 1.0f);
    bits |= std::uint32_t(std::lround(w * 255.0f)) << (8 * m);
  }
  return std::bit_cast<float>(bits);
}

std::array<float, 4> unpackMaterials(float packed) {
  const auto bits = std::bit_cast<std::uint32_t>(packed);
  std::array<float, 4> out{};
  for (std::size_t m = 0; m < 4; ++m) out[m] = float((bits >> (8 * m)) & 255u) / 255.0f;
  return out;
}

namespace {

// A blended normal made unit length again; `fallback` where the blend cancelled out.
void renormalise(std::array<float, 4>& normal, const std::array<float, 4>& fallback) {
  const float length = std::sqrt(normal[0] * normal[0] + normal[1] * normal[1] + normal[2] * normal[2]);
  if (!(length > 0.0f)) {
    normal = fallback;
    return;
  }
  for (std::size_t a = 0; a < 3; ++a) normal[a] /= length;
}

}  // namespace

StackVertex seamBlendedVertex(const StackVertex& own, const StackVertex& target, float weight) {
  if (!(weight > 0.0f)) return own;
  StackVertex out = own;
  const auto blend = [weight](float to, float from) { return to * weight + from * (1.0f - weight); };
  for (std::size_t a = 0; a < 3; ++a) {
    out.position[a] = blend(target.position[a], own.position[a]);
    out.normal[a] = blend(target.normal[a], own.normal[a]);
  }
  renormalise(out.normal, own.normal);
  for (std::size_t m = 0; m < 4; ++m) out.materials[m] = blend(target.materials[m], own.materials[m]);
  return out;
}

float morphKeep(const MorphTarget& target, float morphFactor, std::uint32_t unlikeNeighbours) {
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
  return pinned ? 1.0f : morphFactor;
}

StackVertex drawnStackVertex(const StackVertex& own, const MorphTarget& target, float morphFactor,
                             std::uint32_t unlikeNeighbours) {
  const float keep = morphKeep(target, morphFactor, unlikeNeighbours);
  if (!(keep < 1.0f)) return own;
  StackVertex out = own;
  const auto blend = [keep](float to, float from) { return to * (1.0f - keep) + from * keep; };
  for (std::size_t a = 0; a < 3; ++a) {
    out.position[a] = blend(target[a], own.position[a]);
    out.normal[a] = blend(target[4 + a], own.normal[a]);
  }
  renormalise(out.normal, own.normal);
  const std::array<float, 4> materials = unpackMaterials(target[7]);
  for (std::size_t m = 0; m < 4; ++m) out.materials[m] = blend(materials[m], own.materials[m]);
  return out;
}

std::array<float, 3> drawnStackVertexPosition(const std::array<float, 3>& own,
                                              const MorphTarget& target, float morphFactor,
                                              std::uint32_t unlikeNeighbours) {
  StackVertex vertex;
  for (std::size_t a = 0; a < 3; ++a) vertex.position[a] = own[a];
  const StackVertex drawn = drawnStackVertex(vertex, target, morphFactor, unlikeNeighbours);
  return {drawn.position[0], drawn.position[1], drawn.position[2]};
}

}  // namespace tellus
