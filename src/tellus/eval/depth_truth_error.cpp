#include "tellus/eval/depth_truth_error.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <limits>
#include <optional>
#include <vector>

#include <glm/glm.hpp>
#include <tbb/parallel_for.h>

namespace tellus {

namespace {

// The truth image as world points and unit normals facing the camera (zero where the pixel or
// both its neighbours along an axis are empty).
struct TruthSamples {
  int width = 0, height = 0;
  std::vector<glm::dvec3> points;
  std::vector<glm::dvec3> normals;
  std::vector<double> spacings;  // metres to the farther of the two neighbours the normal was made from
  std::size_t index(int x, int y) const { return std::size_t(y) * std::size_t(width) + std::size_t(x); }
};

// The tangent along one image axis at `p`: towards whichever neighbour (before or after) lies
// nearer in the world, so that a depth step on one side does not bend it.
std::optional<glm::dvec3> tangentAt(const glm::dvec3& p, const glm::dvec3* before, const glm::dvec3* after) {
  if (!before && !after) return std::nullopt;
  if (!before) return *after - p;
  if (!after) return p - *before;
  const glm::dvec3 forward = *after - p, backward = p - *before;
  return glm::dot(forward, forward) <= glm::dot(backward, backward) ? forward : backward;
}

TruthSamples truthSamples(const DepthImage& truth, const ViewSetup& view) {
  TruthSamples s;
  s.width = truth.width;
  s.height = truth.height;
  const std::size_t n = std::size_t(truth.width) * std::size_t(truth.height);
  s.points.assign(n, glm::dvec3(0.0));
  s.normals.assign(n, glm::dvec3(0.0));
  s.spacings.assign(n, 0.0);
  tbb::parallel_for(0, truth.height, [&](int y) {
    for (int x = 0; x < truth.width; ++x) {
      const float d = truth.at(x, y);
      if (d > 0.0f) s.points[s.index(x, y)] = view.unprojectPixel({x + 0.5, y + 0.5}, d);
    }
  });
  const auto pointAt = [&](int x, int y) -> const glm::dvec3* {
    if (x < 0 || y < 0 || x >= truth.width || y >= truth.height || truth.at(x, y) <= 0.0f) return nullptr;
    return &s.points[s.index(x, y)];
  };
  tbb::parallel_for(0, truth.height, [&](int y) {
    for (int x = 0; x < truth.width; ++x) {
      const glm::dvec3* p = pointAt(x, y);
      if (!p) continue;
      const std::optional<glm::dvec3> ex = tangentAt(*p, pointAt(x - 1, y), pointAt(x + 1, y));
      const std::optional<glm::dvec3> ey = tangentAt(*p, pointAt(x, y - 1), pointAt(x, y + 1));
      if (!ex || !ey) continue;
      const glm::dvec3 c = glm::cross(*ex, *ey);
      const double length = glm::length(c);
      if (!(length > 0.0)) continue;
      glm::dvec3 normal = c / length;
      if (glm::dot(normal, view.camera.position - *p) < 0.0) normal = -normal;
      s.normals[s.index(x, y)] = normal;
      s.spacings[s.index(x, y)] = std::max(glm::length(*ex), glm::length(*ey));
    }
  });
  return s;
}

// Where `p` moves onto the plane through `point` with unit normal `normal`: straight down or up,
// as the flat world's measure moves a drawn point, unless the plane is steeper than 78 degrees
// (walls, where a vertical line may never meet it): then along the normal.
constexpr double kSteepestVerticalDropNz = 0.2;  // |n.z| below this: slopes over 78 degrees
glm::dvec3 footOnPlane(const glm::dvec3& p, const glm::dvec3& point, const glm::dvec3& normal) {
  const double offset = glm::dot(p - point, normal);
  if (std::abs(normal.z) >= kSteepestVerticalDropNz) return p - glm::dvec3(0.0, 0.0, offset / normal.z);
  return p - offset * normal;
}

// The seed's extent of the distance between the two points on one ray, at the nearer one.
double alongRayPx(const glm::dvec3& drawn, const glm::dvec3& truth, const ViewSetup& view, double pixelsPerRadian) {
  const double nearer = std::min(glm::distance(drawn, view.camera.position), glm::distance(truth, view.camera.position));
  return glm::distance(drawn, truth) * pixelsPerRadian / std::max(nearer, 1e-6);
}

// The candidate window's offsets, nearest the pixel first: a close candidate usually sets a
// small best extension early, and the farther ones are then rejected before their projection.
struct WindowOffset {
  int dx = 0, dy = 0;
  double lengthPx = 0.0;  // |q - p|: the same value glm::distance gives for the pixel centres
};
constexpr int kWindowSide = 2 * kDepthTruthWindowPx + 1;
const std::array<WindowOffset, kWindowSide * kWindowSide>& windowNearestFirst() {
  static const std::array<WindowOffset, kWindowSide * kWindowSide> offsets = [] {
    std::array<WindowOffset, kWindowSide * kWindowSide> o{};
    std::size_t i = 0;
    for (int dy = -kDepthTruthWindowPx; dy <= kDepthTruthWindowPx; ++dy) {
      for (int dx = -kDepthTruthWindowPx; dx <= kDepthTruthWindowPx; ++dx) {
        o[i++] = {dx, dy, glm::distance(glm::dvec2(dx, dy), glm::dvec2(0.0))};
      }
    }
    std::stable_sort(o.begin(), o.end(), [](const WindowOffset& a, const WindowOffset& b) {
      return a.dx * a.dx + a.dy * a.dy < b.dx * b.dx + b.dy * b.dy;
    });
    return o;
  }();
  return offsets;
}

}  // namespace

ScreenSpaceError measureDepthTruthError(const DepthImage& drawn, const DepthImage& truth, const ViewSetup& view) {
  ScreenSpaceError result;
  result.errorPx.assign(drawn.depth.size(), -1.0f);
  if (drawn.width != truth.width || drawn.height != truth.height) return result;
  if (drawn.depth == truth.depth) {  // the truth itself, or a frame that did not change: exact
    for (std::size_t i = 0; i < drawn.depth.size(); ++i) {
      if (drawn.depth[i] > 0.0f) result.errorPx[i] = 0.0f;
    }
    result.summary = summariseErrors(result.errorPx);
    return result;
  }
  const TruthSamples samples = truthSamples(truth, view);
  const double pixelsPerRadian = double(drawn.height) / (2.0 * std::tan(glm::radians(view.camera.fovYDeg) * 0.5));
  constexpr double kPlaneReachPx = 1.5;  // how far beyond its pixel a tangent plane is trusted
  constexpr double kSeenPx = 0.75;       // a foot this near a pixel's centre is what it sees
  tbb::parallel_for(0, drawn.height, [&](int y) {
    for (int x = 0; x < drawn.width; ++x) {
      const float a = drawn.at(x, y), b = truth.at(x, y);
      if (a <= 0.0f || b <= 0.0f) continue;  // drawn in one image only
      float& error = result.errorPx[samples.index(x, y)];
      if (a == b) {
        error = 0.0f;
        continue;
      }
      const glm::dvec2 pixel{x + 0.5, y + 0.5};
      const glm::dvec3 p = view.unprojectPixel(pixel, a);
      // The best candidate so far: the least extended plane (a foot within kSeenPx of the pixel
      // that sees its plane counts as not extended at all), then the nearest foot, then (exact
      // ties) the first truth pixel in row order, so the result does not depend on the order
      // the window is visited in.
      double bestExtension = std::numeric_limits<double>::infinity();
      double bestOffset = std::numeric_limits<double>::infinity();
      std::size_t bestIndex = std::numeric_limits<std::size_t>::max();
      std::optional<glm::dvec2> footPixel;
      for (const WindowOffset& o : windowNearestFirst()) {
        const int qx = x + o.dx, qy = y + o.dy;
        if (qx < 0 || qy < 0 || qx >= drawn.width || qy >= drawn.height) continue;
        const std::size_t qi = samples.index(qx, qy);
        const glm::dvec3& normal = samples.normals[qi];
        if (normal == glm::dvec3(0.0)) continue;
        const glm::dvec3& point = samples.points[qi];
        const double spacing = std::max(samples.spacings[qi], 1e-9);
        const double reachPx = o.lengthPx + kPlaneReachPx;
        // A candidate whose world reach is beyond both the reach allowed and the best extension
        // so far is out, told without a square root (with a margin for rounding: the exact
        // tests below decide the rest). A vertical drop keeps p's x and y, so its reach is at
        // least their distance from the point's: told before the foot is worked out.
        const double limit = std::min(reachPx, bestExtension) * spacing;
        const double limitSquared = limit * limit * (1.0 + 1e-9);
        const bool vertical = std::abs(normal.z) >= kSteepestVerticalDropNz;
        if (vertical) {
          const glm::dvec2 across(p.x - point.x, p.y - point.y);
          if (glm::dot(across, across) > limitSquared) continue;
        }
        const glm::dvec3 foot = footOnPlane(p, point, normal);
        const glm::dvec3 footToPoint = foot - point;
        if (glm::dot(footToPoint, footToPoint) > limitSquared) continue;
        // How far the plane is extended to reach the foot, in pixels of q's patch: on screen,
        // and in the world (a plane seen at a grazing angle reaches far along the view rays
        // while staying on one pixel), in units of the spacing of q's neighbours.
        const glm::dvec2 q{qx + 0.5, qy + 0.5};
        const double reachWorld = glm::length(footToPoint) / spacing;
        if (reachWorld > reachPx) continue;
        // The extension is at least the world reach: a candidate already beaten is not
        // projected.
        if (std::max(reachWorld, kSeenPx) > bestExtension) continue;
        glm::dvec2 projected;
        if (!view.projectToPixel(foot, projected)) continue;
        const double reachScreen = glm::distance(projected, q);
        if (reachScreen > reachPx) continue;
        const double extension = std::max({reachScreen, reachWorld, kSeenPx});
        const double offset = glm::distance(p, foot);
        if (extension > bestExtension) continue;
        if (extension == bestExtension && (offset > bestOffset || (offset == bestOffset && qi > bestIndex))) {
          continue;
        }
        bestExtension = extension;
        bestOffset = offset;
        bestIndex = qi;
        footPixel = projected;
      }
      error = float(footPixel ? glm::distance(*footPixel, pixel)
                              : alongRayPx(p, samples.points[samples.index(x, y)], view, pixelsPerRadian));
    }
  });
  result.summary = summariseErrors(result.errorPx);
  return result;
}

}  // namespace tellus
