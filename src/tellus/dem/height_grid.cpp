#include "tellus/dem/height_grid.hpp"

#include <algorithm>
#include <cmath>

namespace tellus {

HeightRange HeightGrid::heightRange() const {
  if (heights.empty()) return {};
  const auto [lo, hi] = std::minmax_element(heights.begin(), heights.end());
  return {*lo, *hi};
}

Aabb HeightGrid::worldBounds() const {
  const HeightRange range = heightRange();
  return Aabb{{0.0, 0.0, range.minM},
              {(width - 1) * spacingXM, (height - 1) * spacingYM, range.maxM}};
}

float HeightGrid::heightAtWorld(double x, double y) const {
  const double col = std::clamp(x / spacingXM, 0.0, double(width - 1));
  const double row = std::clamp(double(height - 1) - y / spacingYM, 0.0, double(height - 1));
  const int c0 = std::min(int(col), width - 2 < 0 ? 0 : width - 2);
  const int r0 = std::min(int(row), height - 2 < 0 ? 0 : height - 2);
  const int c1 = std::min(c0 + 1, width - 1), r1 = std::min(r0 + 1, height - 1);
  const float fx = float(col - c0), fy = float(row - r0);
  const float top = at(c0, r0) * (1.0f - fx) + at(c1, r0) * fx;
  const float bottom = at(c0, r1) * (1.0f - fx) + at(c1, r1) * fx;
  return top * (1.0f - fy) + bottom * fy;
}

double HeightGrid::meshHeightAtWorld(double x, double y) const {
  const double col = std::clamp(x / spacingXM, 0.0, double(width - 1));
  const double row = std::clamp(double(height - 1) - y / spacingYM, 0.0, double(height - 1));
  const int c0 = std::min(int(col), std::max(width - 2, 0));
  const int r0 = std::min(int(row), std::max(height - 2, 0));
  const int c1 = std::min(c0 + 1, width - 1), r1 = std::min(r0 + 1, height - 1);
  const double fx = col - c0, fy = row - r0;  // fy grows southwards (with the row)
  const double h00 = at(c0, r0), h10 = at(c1, r0), h01 = at(c0, r1), h11 = at(c1, r1);
  // Diagonal (c0 + 1, r0) - (c0, r0 + 1): triangle (00, 10, 01) where fx + fy <= 1.
  if (fx + fy <= 1.0) return h00 + (h10 - h00) * fx + (h01 - h00) * fy;
  return h11 + (h01 - h11) * (1.0 - fx) + (h10 - h11) * (1.0 - fy);
}

}  // namespace tellus
