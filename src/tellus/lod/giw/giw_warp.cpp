#include "tellus/core/stopwatch.hpp"
#include "tellus/lod/giw/giw_warp.hpp"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>

#include <glm/geometric.hpp>
#include <glm/mat4x4.hpp>
#include <glm/vec4.hpp>
#include <tbb/parallel_for.h>

namespace tellus::giw {
namespace {

// Positions along one piecewise-linear function so that each of the n - 1 intervals holds the
// same share of its importance: `weights` (n values at unit spacing, > 0) blended with the
// uniform share, integrated by trapezoids and inverted. Returns n parameters in [0, n - 1],
// strictly increasing, first 0 and last n - 1.
void equalShares(const float* weights, std::size_t stride, int n, float uniformShare, std::vector<double>& cumulative,
                 std::vector<double>& out) {
  double mean = 0.0;
  for (int i = 0; i < n; ++i) mean += weights[std::size_t(i) * stride];
  mean /= n;
  const auto w = [&](int i) { return double(weights[std::size_t(i) * stride]) * (1.0 - uniformShare) + mean * uniformShare; };
  cumulative.assign(std::size_t(n), 0.0);
  for (int i = 1; i < n; ++i) cumulative[std::size_t(i)] = cumulative[std::size_t(i) - 1] + 0.5 * (w(i - 1) + w(i));
  const double total = cumulative.back();
  out.assign(std::size_t(n), 0.0);
  int segment = 0;
  for (int k = 0; k < n; ++k) {
    const double target = total * k / (n - 1);
    while (segment < n - 2 && cumulative[std::size_t(segment) + 1] < target) ++segment;
    const double a = cumulative[std::size_t(segment)], b = cumulative[std::size_t(segment) + 1];
    const double f = b > a ? std::clamp((target - a) / (b - a), 0.0, 1.0) : 0.0;
    out[std::size_t(k)] = segment + f;
  }
  out.front() = 0.0;
  out.back() = n - 1;
}

}  // namespace

Status checkSettings(const GiwSettings& s) {
  if (s.size < 9 || s.size > 2049) return makeError("geometry image size {} is outside [9, 2049]", s.size);
  if (!(s.slopeWeight >= 0.0f) || !(s.outsideImportance > 0.0f)) {
    return makeError("geometry image warping: the slope weight must be >= 0 and the outside importance > 0");
  }
  if (!(s.uniformShare >= 0.0f && s.uniformShare <= 1.0f)) return makeError("geometry image warping: the uniform share must be in [0, 1]");
  return {};
}

Region viewRegion(const HeightGrid& grid, float lowestM, const ViewSetup& view, float exaggeration) {
  const Region whole{{0.0, 0.0}, {double(grid.width - 1), double(grid.height - 1)}};
  const double lowZ = double(lowestM) * exaggeration;
  const glm::dvec3 eye = view.camera.position;
  glm::dvec2 lo = glm::dvec2(eye), hi = glm::dvec2(eye);
  for (const glm::dvec2 ndc : {glm::dvec2(-1, -1), glm::dvec2(1, -1), glm::dvec2(-1, 1), glm::dvec2(1, 1)}) {
    // The corner ray (camera-relative): through the near plane (reversed Z: depth 1) and a
    // point further out.
    glm::dvec4 a = view.inverseViewProjection * glm::dvec4(ndc, 1.0, 1.0);
    glm::dvec4 b = view.inverseViewProjection * glm::dvec4(ndc, 0.5, 1.0);
    const glm::dvec3 direction = glm::normalize(glm::dvec3(b) / b.w - glm::dvec3(a) / a.w);
    if (direction.z >= -1e-9 || eye.z <= lowZ) return whole;  // sees above the lowest ground: unbounded
    const double t = (lowZ - eye.z) / direction.z;
    const glm::dvec2 hit = glm::dvec2(eye) + t * glm::dvec2(direction);
    lo = glm::min(lo, hit);
    hi = glm::max(hi, hit);
  }
  const glm::dvec2 spacing{grid.spacingXM, grid.spacingYM};
  Region r{glm::clamp(lo / spacing, whole.min, whole.max), glm::clamp(hi / spacing, whole.min, whole.max)};
  // At least a few samples wide (a view straight down from low altitude).
  for (int axis = 0; axis < 2; ++axis) {
    if (r.max[axis] - r.min[axis] < 4.0) {
      const double c = std::clamp(0.5 * (r.min[axis] + r.max[axis]), whole.min[axis] + 2.0, whole.max[axis] - 2.0);
      r.min[axis] = std::max(whole.min[axis], c - 2.0);
      r.max[axis] = std::min(whole.max[axis], c + 2.0);
    }
  }
  return r;
}

std::vector<float> importanceMap(const HeightGrid& grid, const Region& region, const LodView& view,
                                 const GiwSettings& settings) {
  const int n = settings.size;
  std::vector<float> importance(std::size_t(n) * std::size_t(n));
  const glm::dvec2 step = (region.max - region.min) / double(n - 1);
  const double exaggeration = view.exaggeration;
  tbb::parallel_for(0, n, [&](int j) {
    for (int i = 0; i < n; ++i) {
      const glm::dvec2 g = region.min + glm::dvec2(i, j) * step;  // grid units
      const double x = g.x * grid.spacingXM, y = g.y * grid.spacingYM;
      const double h = double(grid.heightAtWorld(x, y)) * exaggeration;
      // Slope from the sketch's own spacing (at least a grid sample).
      const double dx = std::max(step.x, 1.0) * grid.spacingXM, dy = std::max(step.y, 1.0) * grid.spacingYM;
      const double gx = (double(grid.heightAtWorld(x + dx, y)) - double(grid.heightAtWorld(x - dx, y))) * exaggeration / (2 * dx);
      const double gy = (double(grid.heightAtWorld(x, y + dy)) - double(grid.heightAtWorld(x, y - dy))) * exaggeration / (2 * dy);
      const glm::dvec3 normal = glm::normalize(glm::dvec3(-gx, -gy, 1.0));
      const glm::dvec3 toEye = view.cameraM - glm::dvec3(x, y, h);
      const double distance = std::max(view.nearM, glm::length(toEye));
      const double facing = std::abs(glm::dot(normal, toEye / distance));
      const double slope = std::sqrt(gx * gx + gy * gy);
      const glm::dvec3 relative = glm::dvec3(x, y, h) - view.cameraM;
      bool inside = true;
      for (const glm::dvec4& plane : view.frustum.planes()) inside = inside && glm::dot(glm::dvec3(plane), relative) + plane.w >= 0.0;
      const double value = (inside ? 1.0 : double(settings.outsideImportance)) * (1.0 + settings.slopeWeight * std::min(slope, 2.0)) *
                           (0.25 + facing) / distance;
      importance[std::size_t(j) * std::size_t(n) + std::size_t(i)] = float(std::max(value, 1e-30));
    }
  });
  return importance;
}

std::vector<glm::dvec2> warpRowsThenColumns(const std::vector<float>& importance, int n, float uniformShare) {
  std::vector<glm::dvec2> rows(std::size_t(n) * std::size_t(n));
  // Rows: each row's samples moved to equal shares of its importance.
  tbb::parallel_for(0, n, [&](int j) {
    std::vector<double> cumulative, x;
    equalShares(&importance[std::size_t(j) * std::size_t(n)], 1, n, uniformShare, cumulative, x);
    for (int i = 0; i < n; ++i) rows[std::size_t(j) * std::size_t(n) + std::size_t(i)] = {x[std::size_t(i)], double(j)};
  });
  // Columns: one distribution for all of them, from each row's total importance, so that every
  // output row lies at one height across the image. Rows are then horizontal lines with x
  // strictly increasing along each, and no quad can fold over (a per-column distribution, as
  // the paper's, shears neighbouring columns past each other where importance changes fast).
  std::vector<float> rowTotals(std::size_t(n), 0.0f);
  for (int j = 0; j < n; ++j) {
    double total = 0.0;
    for (int i = 0; i < n; ++i) total += importance[std::size_t(j) * std::size_t(n) + std::size_t(i)];
    rowTotals[std::size_t(j)] = float(total);
  }
  std::vector<double> cumulative, t;
  equalShares(rowTotals.data(), 1, n, uniformShare, cumulative, t);
  std::vector<glm::dvec2> out(rows.size());
  tbb::parallel_for(0, n, [&](int k) {
    const int j = std::min(int(t[std::size_t(k)]), n - 2);
    const double f = t[std::size_t(k)] - j;
    for (int i = 0; i < n; ++i) {
      const glm::dvec2 a = rows[std::size_t(j) * std::size_t(n) + std::size_t(i)];
      const glm::dvec2 b = rows[std::size_t(j + 1) * std::size_t(n) + std::size_t(i)];
      out[std::size_t(k) * std::size_t(n) + std::size_t(i)] = {a.x + (b.x - a.x) * f, t[std::size_t(k)]};
    }
  });
  return out;
}

GeometryImage buildGeometryImage(const HeightGrid& grid, float lowestM, const ViewSetup& view, float exaggeration,
                                 const GiwSettings& settings) {
  GeometryImage image;
  image.size = settings.size;
  const int n = settings.size;
  const LodView lod = LodView::fromSetup(view, exaggeration);
  image.region = viewRegion(grid, lowestM, view, exaggeration);
  Stopwatch stage;
  const std::vector<float> importance = importanceMap(grid, image.region, lod, settings);
  image.importanceMs = stage.lapMs();
  const std::vector<glm::dvec2> warped = warpRowsThenColumns(importance, n, settings.uniformShare);
  image.warpMs = stage.lapMs();
  const glm::dvec2 step = (image.region.max - image.region.min) / double(n - 1);
  image.vertices.resize(warped.size());
  image.density.resize(warped.size());
  tbb::parallel_for(0, n, [&](int j) {
    for (int i = 0; i < n; ++i) {
      const std::size_t k = std::size_t(j) * std::size_t(n) + std::size_t(i);
      const glm::dvec2 g = image.region.min + warped[k] * step;
      image.vertices[k] = glm::vec3(float(g.x), float(g.y), grid.heightAtWorld(g.x * grid.spacingXM, g.y * grid.spacingYM));
      // Density: the even cell's area over the warped cell's (from the neighbouring vertices).
      const int i1 = std::min(i + 1, n - 1), i0 = i1 - 1, j1 = std::min(j + 1, n - 1), j0 = j1 - 1;
      const glm::dvec2 du = warped[std::size_t(j) * std::size_t(n) + std::size_t(i1)] - warped[std::size_t(j) * std::size_t(n) + std::size_t(i0)];
      const glm::dvec2 dv = warped[std::size_t(j1) * std::size_t(n) + std::size_t(i)] - warped[std::size_t(j0) * std::size_t(n) + std::size_t(i)];
      const double area = std::abs(du.x * dv.y - du.y * dv.x);
      image.density[k] = float(area > 0.0 ? 1.0 / area : 1.0);
    }
  });
  image.resampleMs = stage.lapMs();
  return image;
}

}  // namespace tellus::giw
