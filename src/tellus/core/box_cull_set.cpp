#include "tellus/core/box_cull_set.hpp"

#include <algorithm>
#include <cmath>
#include <array>
#include <limits>

#include <glm/geometric.hpp>

namespace tellus {

BoxCullSet::BoxCullSet(std::span<const Aabb> boxes) {
  if (boxes.empty()) return;
  Aabb bounds{glm::dvec3(std::numeric_limits<double>::max()), glm::dvec3(std::numeric_limits<double>::lowest())};
  for (const Aabb& box : boxes) {
    bounds.min = glm::min(bounds.min, box.min);
    bounds.max = glm::max(bounds.max, box.max);
  }
  origin_ = bounds.centre();
  radius_ = 0.5 * glm::length(bounds.size());
  for (auto* column : {&centreX_, &centreY_, &centreZ_, &halfX_, &halfY_, &halfZ_}) column->resize(boxes.size());
  for (std::size_t i = 0; i < boxes.size(); ++i) {
    const glm::dvec3 centre = boxes[i].centre() - origin_, half = 0.5 * boxes[i].size();
    centreX_[i] = float(centre.x);
    centreY_[i] = float(centre.y);
    centreZ_[i] = float(centre.z);
    halfX_[i] = float(half.x);
    halfY_[i] = float(half.y);
    halfZ_[i] = float(half.z);
  }
}

namespace {

// The test over arrays. Inlined into two versions: the baseline x86-64 one (4 boxes an
// instruction) and, where the CPU has AVX2, one compiled for it (8), picked at run time (no
// ifunc: the sanitizers' runtimes do not start before an ifunc resolver runs).
struct Planes {
  std::array<float, 6> x, y, z, w, absX, absY, absZ;
};

struct BoxArrays {
  const float *cx, *cy, *cz, *hx, *hy, *hz;
  std::size_t n;
};

[[gnu::always_inline]] inline void markBoxesBody(const Planes& planes, const BoxArrays& boxes, float ox, float oy,
                                                 float oz, float e, float slack, std::uint8_t bit, std::uint8_t* out) {
  // Local, unaliased copies: the flags are bytes, which may alias anything, and would otherwise
  // make the compiler reload the arrays' addresses after every store (and not vectorise).
  const float* __restrict cxs = boxes.cx;
  const float* __restrict cys = boxes.cy;
  const float* __restrict czs = boxes.cz;
  const float* __restrict hxs = boxes.hx;
  const float* __restrict hys = boxes.hy;
  const float* __restrict hzs = boxes.hz;
  std::uint8_t* __restrict flags = out;
  const Planes p = planes;
  const std::size_t n = boxes.n;
  for (std::size_t i = 0; i < n; ++i) {
    const float cx = cxs[i] + ox, cy = cys[i] + oy, cz = czs[i] * e + oz;
    const float hx = hxs[i] + slack, hy = hys[i] + slack, hz = hzs[i] * e + slack;
    // Per plane, the distance of the box corner farthest along the normal (the centre's plus
    // the extent's); the box is inside unless one is negative.
    float nearest = std::numeric_limits<float>::max();
    for (std::size_t k = 0; k < 6; ++k) {
      const float d = p.x[k] * cx + p.y[k] * cy + p.z[k] * cz + p.w[k] + p.absX[k] * hx + p.absY[k] * hy +
                      p.absZ[k] * hz;
      nearest = std::min(nearest, d);
    }
    flags[i] |= nearest >= 0.0f ? bit : std::uint8_t(0);
  }
}

#if defined(__x86_64__) && defined(__GNUC__)
#define TELLUS_BOX_CULL_AVX2 1
[[gnu::target("avx2")]] void markBoxesAvx2(const Planes& planes, const BoxArrays& boxes, float ox, float oy, float oz,
                                           float e, float slack, std::uint8_t bit, std::uint8_t* out) {
  markBoxesBody(planes, boxes, ox, oy, oz, e, slack, bit, out);
}
#endif

void markBoxes(const Planes& planes, const BoxArrays& boxes, float ox, float oy, float oz, float e, float slack,
               std::uint8_t bit, std::uint8_t* out) {
#ifdef TELLUS_BOX_CULL_AVX2
  static const bool avx2 = __builtin_cpu_supports("avx2");
  if (avx2) {
    markBoxesAvx2(planes, boxes, ox, oy, oz, e, slack, bit, out);
    return;
  }
#endif
  markBoxesBody(planes, boxes, ox, oy, oz, e, slack, bit, out);
}

}  // namespace

void BoxCullSet::markInside(const Frustum& frustum, const glm::dvec3& camera, double exaggeration,
                            std::uint8_t bit, std::vector<std::uint8_t>& flags) const {
  const std::size_t n = size();
  flags.resize(n, 0);
  if (n == 0) return;
  // Box i, camera-relative and exaggerated: centre (cx + ox, cy + oy, cz * e + oz), half
  // extent (hx, hy, hz * e), with o the origin relative to the camera.
  const float ox = float(origin_.x - camera.x), oy = float(origin_.y - camera.y);
  const float oz = float(origin_.z * exaggeration - camera.z);
  const float e = float(exaggeration);
  // Float rounding in the plane distances: a few ulps of the largest distance involved, made
  // up for by widening every box (so rounding can only keep a box, never drop one).
  const double reach = glm::length(origin_ - camera) + radius_ * std::max(1.0, exaggeration) +
                       std::abs(origin_.z) * std::abs(exaggeration - 1.0);
  const float slack = float(reach * 1e-6) + 1e-4f;
  Planes planes{};
  for (std::size_t k = 0; k < 6; ++k) {
    const glm::dvec4& p = frustum.planes()[k];
    planes.x[k] = float(p.x);
    planes.y[k] = float(p.y);
    planes.z[k] = float(p.z);
    planes.w[k] = float(p.w);
    planes.absX[k] = std::abs(planes.x[k]);
    planes.absY[k] = std::abs(planes.y[k]);
    planes.absZ[k] = std::abs(planes.z[k]);
  }
  const BoxArrays boxes{centreX_.data(), centreY_.data(), centreZ_.data(), halfX_.data(), halfY_.data(), halfZ_.data(), n};
  markBoxes(planes, boxes, ox, oy, oz, e, slack, bit, flags.data());
}

}  // namespace tellus
