#include "tellus/formats/stacks/stack_edit.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "tellus/formats/stacks/stack_aggregation.hpp"

namespace tellus {

std::vector<StackLayer> fillInterval(std::span<const StackLayer> column, float bottomM,
                                     float topM, StackMaterial material) {
  // What of each layer lies outside [bottomM, topM), and the interval itself, bottom up.
  std::vector<StackLayer> pieces;
  for (const StackLayer& layer : column) {
    pieces.push_back({layer.bottomM, std::min(layer.topM, bottomM), layer.material});
    pieces.push_back({std::max(layer.bottomM, topM), layer.topM, layer.material});
  }
  pieces.push_back({bottomM, topM, material});
  std::sort(pieces.begin(), pieces.end(),
            [](const StackLayer& a, const StackLayer& b) { return a.bottomM < b.bottomM; });
  std::vector<StackLayer> out;
  for (const StackLayer& piece : pieces) {
    if (!(piece.topM > piece.bottomM) || piece.material == kAir) continue;
    if (!out.empty() && out.back().material == piece.material && out.back().topM == piece.bottomM) {
      out.back().topM = piece.topM;
    } else {
      out.push_back(piece);
    }
  }
  return out;
}

Status checkSphereEdit(const StackTerrain& terrain, const SphereEdit& edit) {
  if (!std::isfinite(edit.xM) || !std::isfinite(edit.yM) || !std::isfinite(edit.zM) ||
      !std::isfinite(edit.radiusM)) {
    return makeError("the sphere's centre and radius must be finite numbers");
  }
  if (!(edit.radiusM > 0.0)) return makeError("the sphere's radius must be positive (got {} m)", edit.radiusM);
  const double s = terrain.spacingM();
  const double maxX = (terrain.width() - 1) * s, maxY = (terrain.height() - 1) * s;
  if (edit.xM + edit.radiusM < 0.0 || edit.xM - edit.radiusM > maxX ||
      edit.yM + edit.radiusM < 0.0 || edit.yM - edit.radiusM > maxY) {
    return makeError("the sphere at ({:.1f}, {:.1f}) m with radius {:.1f} m misses the terrain (x "
                     "0..{:.1f} m, y 0..{:.1f} m)", edit.xM, edit.yM, edit.radiusM, maxX, maxY);
  }
  if (edit.zM + edit.radiusM <= 0.0) {
    return makeError("the sphere lies under the terrain's base (z {} m, radius {} m)", edit.zM,
                     edit.radiusM);
  }
  if (edit.zM - edit.radiusM > 1e6) return makeError("the sphere lies above 1000 km");
  // A sphere larger than the terrain's whole box changes nothing more than one as large as the
  // box; beyond that its extent in stacks would overflow the column arithmetic.
  const double extent = std::max({maxX, maxY, double(terrain.topM()), s});
  const double largest = 4.0 * extent;
  if (edit.radiusM > largest || std::abs(edit.xM) > largest + maxX || std::abs(edit.yM) > largest + maxY ||
      std::abs(edit.zM) > 1e6) {
    return makeError("the sphere at ({:.4g}, {:.4g}, {:.4g}) m with radius {:.4g} m is far beyond the "
                     "terrain ({:.1f} x {:.1f} m, {:.1f} m tall): its radius may be at most {:.1f} m",
                     edit.xM, edit.yM, edit.zM, edit.radiusM, maxX, maxY, terrain.topM(), largest);
  }
  return {};
}

Result<StackRegion> applySphereEdit(StackTerrain& terrain, const SphereEdit& edit) {
  if (Status ok = checkSphereEdit(terrain, edit); !ok) return ok.error();
  const double s = terrain.spacingM();
  const int w = terrain.width(), h = terrain.height();
  // Columns (x) and sample rows (y north) within the disc's box.
  const int cx0 = std::max(0, int(std::ceil((edit.xM - edit.radiusM) / s)));
  const int cx1 = std::min(w - 1, int(std::floor((edit.xM + edit.radiusM) / s)));
  const int sy0 = std::max(0, int(std::ceil((edit.yM - edit.radiusM) / s)));
  const int sy1 = std::min(h - 1, int(std::floor((edit.yM + edit.radiusM) / s)));
  StackRegion region;
  if (cx0 > cx1 || sy0 > sy1) return region;
  // The disc's box in terrain rows (row 0 north), edited column by column.
  const StackRegion box{cx0, h - 1 - sy1, cx1, h - 1 - sy0};
  bool any = false;
  std::vector<std::vector<StackLayer>> edited;
  edited.reserve(std::size_t(box.x1 - box.x0 + 1) * std::size_t(box.y1 - box.y0 + 1));
  for (int row = box.y0; row <= box.y1; ++row) {
    for (int x = box.x0; x <= box.x1; ++x) {
      const std::span<const StackLayer> column = terrain.column(x, row);
      const int sy = h - 1 - row;
      const double dx = x * s - edit.xM, dy = sy * s - edit.yM;
      const double d2 = edit.radiusM * edit.radiusM - dx * dx - dy * dy;
      const double half = d2 >= 0.0 ? std::sqrt(d2) : 0.0;
      const float bottom = float(std::max(0.0, edit.zM - half)), top = float(edit.zM + half);
      if (d2 < 0.0 || !(top > bottom)) {
        edited.emplace_back(column.begin(), column.end());
        continue;
      }
      edited.push_back(fillInterval(column, bottom, top, edit.material));
      if (!std::equal(edited.back().begin(), edited.back().end(), column.begin(), column.end())) {
        if (!any) region = {x, row, x, row};
        region.x0 = std::min(region.x0, x);
        region.x1 = std::max(region.x1, x);
        region.y0 = std::min(region.y0, row);
        region.y1 = std::max(region.y1, row);
        any = true;
      }
    }
  }
  if (!any) return region;
  if (Status replaced = terrain.replaceColumns(box, edited); !replaced) {
    return makeError("the edit made an invalid column: {}", replaced.error().message);
  }
  return region;
}

std::optional<glm::dvec3> firstSolidAlongRay(const StackTerrain& terrain, const glm::dvec3& origin,
                                             const glm::dvec3& direction, double maxM) {
  const double s = terrain.spacingM();
  const auto solidAt = [&](const glm::dvec3& p) {
    const int x = int(std::lround(p.x / s));
    const int row = terrain.height() - 1 - int(std::lround(p.y / s));
    if (x < 0 || row < 0 || x >= terrain.width() || row >= terrain.height()) return false;
    for (const StackLayer& layer : terrain.column(x, row)) {
      if (p.z >= layer.bottomM && p.z < layer.topM) return true;
    }
    return false;
  };
  const double step = 0.25 * s;
  for (double t = 0.0; t <= maxM; t += step) {
    if (!solidAt(origin + t * direction)) continue;
    double outside = std::max(0.0, t - step), inside = t;
    for (int i = 0; i < 20; ++i) {
      const double middle = 0.5 * (outside + inside);
      (solidAt(origin + middle * direction) ? inside : outside) = middle;
    }
    return origin + inside * direction;
  }
  return std::nullopt;
}

std::vector<StackRegion> updatePyramid(std::vector<StackTerrain>& pyramid, StackRegion region) {
  std::vector<StackRegion> changed{region};
  for (std::size_t k = 1; k < pyramid.size() && !region.empty(); ++k) {
    const StackTerrain& fine = pyramid[k - 1];
    StackTerrain& coarse = pyramid[k];
    region = {region.x0 / 2, region.y0 / 2, region.x1 / 2, region.y1 / 2};
    std::vector<std::vector<StackLayer>> aggregated;
    for (int y = region.y0; y <= region.y1; ++y) {
      for (int x = region.x0; x <= region.x1; ++x) {
        std::vector<std::span<const StackLayer>> four;
        for (int dy = 0; dy < 2; ++dy) {
          for (int dx = 0; dx < 2; ++dx) {
            if (2 * x + dx < fine.width() && 2 * y + dy < fine.height()) {
              four.push_back(fine.column(2 * x + dx, 2 * y + dy));
            }
          }
        }
        aggregated.push_back(aggregateColumns(four));
      }
    }
    // Aggregates of valid columns are valid: a failure here is a bug, not bad input.
    if (Status replaced = coarse.replaceColumns(region, aggregated); !replaced) {
      throw std::logic_error("updatePyramid: " + replaced.error().message);
    }
    changed.push_back(region);
  }
  return changed;
}

}  // namespace tellus
