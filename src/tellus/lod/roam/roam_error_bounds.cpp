#include "tellus/lod/roam/roam_error_bounds.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include <glm/common.hpp>

namespace tellus::roam {
namespace {

int ceilDiv(int a, int b) {
  return (a + b - 1) / b;
}

// Computes the bound of node `heap` at `depth` (vertices t), storing it when shallow enough.
float boundRecursive(const HeightGrid& grid, const BintreeDomain& domain, const BintreeTriangle& t,
                     std::uint32_t heap, int depth, std::uint16_t* stored, float& minH,
                     float& maxH) {
  const float apexHeight = heightAt(grid, t.apex);
  minH = std::min(minH, apexHeight);
  maxH = std::max(maxH, apexHeight);
  if (depth == domain.leafDepth()) return 0.0f;
  const float own =
      depth + 1 == domain.leafDepth() ? lastSplitBound(grid, t) : midpointError(grid, t);
  float below = 0.0f;
  if (depth + 1 < domain.leafDepth()) {
    below = std::max(
        boundRecursive(grid, domain, leftChild(t), 2 * heap, depth + 1, stored, minH, maxH),
        boundRecursive(grid, domain, rightChild(t), 2 * heap + 1, depth + 1, stored, minH, maxH));
  } else {
    // The children are leaves: their apex (the midpoint) is a sample of the block too.
    const glm::ivec2 c = (t.left + t.right) / 2;
    const float h = heightAt(grid, c);
    minH = std::min(minH, h);
    maxH = std::max(maxH, h);
  }
  const float bound = below + own;
  if (depth <= domain.leafDepth() - 2) stored[heap] = encodeBound(bound);
  return bound;
}

}  // namespace

BintreeDomain BintreeDomain::forGrid(int gridWidth, int gridHeight, int blockLog2) {
  BintreeDomain d;
  d.blockLog2 = blockLog2;
  d.gridWidth = gridWidth;
  d.gridHeight = gridHeight;
  d.blocksX = std::max(1, ceilDiv(gridWidth - 1, d.blockCells()));
  d.blocksY = std::max(1, ceilDiv(gridHeight - 1, d.blockCells()));
  return d;
}

glm::ivec2 BintreeDomain::clampToGrid(glm::ivec2 uv) const {
  return {std::clamp(uv.x, 0, gridWidth - 1), std::clamp(uv.y, 0, gridHeight - 1)};
}

BintreeTriangle rootTriangle(const BintreeDomain& domain, int bx, int by, int root) {
  const int s = domain.blockCells();
  const glm::ivec2 sw(bx * s, by * s);
  const glm::ivec2 se = sw + glm::ivec2(s, 0), ne = sw + glm::ivec2(s, s), nw = sw + glm::ivec2(0, s);
  return root == 0 ? BintreeTriangle{se, ne, sw} : BintreeTriangle{nw, sw, ne};
}

BintreeTriangle leftChild(const BintreeTriangle& t) {
  return {(t.left + t.right) / 2, t.apex, t.left};
}

BintreeTriangle rightChild(const BintreeTriangle& t) {
  return {(t.left + t.right) / 2, t.right, t.apex};
}

float heightAt(const HeightGrid& grid, glm::ivec2 uv) {
  const int col = std::clamp(uv.x, 0, grid.width - 1);
  const int rowFromSouth = std::clamp(uv.y, 0, grid.height - 1);
  return grid.at(col, grid.height - 1 - rowFromSouth);
}

float midpointError(const HeightGrid& grid, const BintreeTriangle& t) {
  const glm::ivec2 c = (t.left + t.right) / 2;
  return std::abs(heightAt(grid, c) - 0.5f * (heightAt(grid, t.left) + heightAt(grid, t.right)));
}

bool hasDrawnDiagonal(const BintreeTriangle& halfCell) {
  const glm::ivec2 d = halfCell.right - halfCell.left;
  return d.x * d.y > 0;
}

float cellTwist(const HeightGrid& grid, glm::ivec2 southWest) {
  const float sw = heightAt(grid, southWest), ne = heightAt(grid, southWest + glm::ivec2(1, 1));
  const float nw = heightAt(grid, southWest + glm::ivec2(0, 1));
  const float se = heightAt(grid, southWest + glm::ivec2(1, 0));
  return 0.5f * std::abs(sw + ne - nw - se);
}

float lastSplitBound(const HeightGrid& grid, const BintreeTriangle& t) {
  float twist = 0.0f;
  for (const BintreeTriangle& half : {leftChild(t), rightChild(t)}) {
    if (hasDrawnDiagonal(half)) continue;
    const glm::ivec2 southWest = glm::min(half.apex, glm::min(half.left, half.right));
    twist = std::max(twist, cellTwist(grid, southWest));
  }
  return midpointError(grid, t) + twist;
}

BlockBounds computeBlockBounds(const HeightGrid& grid, const BintreeDomain& domain, int bx, int by) {
  BlockBounds out;
  const std::size_t perRoot = domain.storedPerRoot();
  out.bounds.assign(2 * perRoot, 0);
  float minH = std::numeric_limits<float>::max(), maxH = std::numeric_limits<float>::lowest();
  for (int root = 0; root < 2; ++root) {
    const BintreeTriangle t = rootTriangle(domain, bx, by, root);
    for (const glm::ivec2 corner : {t.left, t.right}) {
      const float h = heightAt(grid, corner);
      minH = std::min(minH, h);
      maxH = std::max(maxH, h);
    }
    out.rootBoundM[std::size_t(root)] =
        boundRecursive(grid, domain, t, 1, 0, out.bounds.data() + std::size_t(root) * perRoot, minH, maxH);
  }
  out.minHeightM = minH;
  out.maxHeightM = maxH;
  return out;
}

float decodeBound(std::uint16_t stored) {
  if (stored == std::numeric_limits<std::uint16_t>::max()) return std::numeric_limits<float>::infinity();
  return float(stored) * kBoundStepM;
}

std::uint16_t encodeBound(float metres) {
  const float steps = std::ceil(metres / kBoundStepM);
  if (!(steps < 65535.0f)) return std::numeric_limits<std::uint16_t>::max();
  return std::uint16_t(std::max(0.0f, steps));
}

}  // namespace tellus::roam
