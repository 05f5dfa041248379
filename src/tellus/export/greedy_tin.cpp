#include "tellus/export/greedy_tin.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <queue>
#include <utility>

#include <glm/vec3.hpp>

namespace tellus {
namespace {

constexpr std::int32_t kNone = -1;

std::int32_t nextEdge(std::int32_t e) { return e % 3 == 2 ? e - 2 : e + 1; }
std::int32_t previousEdge(std::int32_t e) { return e % 3 == 0 ? e + 2 : e - 1; }

// The worst point of a triangle: its miss (metres) and the point.
struct Worst {
  double missM = 0.0;
  std::uint32_t point = 0;
};

// The samples of a grid as points: point index = sample index, x = column, y = row; the
// error is vertical, found by rasterising the triangle over the grid.
class GridPoints {
 public:
  explicit GridPoints(const GreedyTinInput& in) : in_(in) {}
  std::size_t count() const { return std::size_t(in_.width) * std::size_t(in_.height); }
  std::int64_t x(std::uint32_t s) const { return std::int64_t(s % std::uint32_t(in_.width)); }
  std::int64_t y(std::uint32_t s) const { return std::int64_t(s / std::uint32_t(in_.width)); }
  double metresPerUnitX() const { return in_.spacingXM; }
  double metresPerUnitY() const { return in_.spacingYM; }
  double maxErrorM() const { return in_.maxErrorM; }
  std::array<std::uint32_t, 4> corners() const {
    return {sampleOf(0, 0), sampleOf(in_.width - 1, 0), sampleOf(in_.width - 1, in_.height - 1),
            sampleOf(0, in_.height - 1)};
  }
  std::vector<std::uint32_t> border() const {
    std::vector<std::uint32_t> points;
    if (!in_.keepBorder) return points;
    for (int col = 1; col + 1 < in_.width; ++col) {
      points.push_back(sampleOf(col, 0));
      points.push_back(sampleOf(col, in_.height - 1));
    }
    for (int row = 1; row + 1 < in_.height; ++row) {
      points.push_back(sampleOf(0, row));
      points.push_back(sampleOf(in_.width - 1, row));
    }
    return points;
  }

  // v: counter-clockwise corners, area: twice their area (> 0).
  Worst worstIn(const std::uint32_t v[3], std::int64_t area) const {
    Worst worst{0.0, v[0]};
    std::int64_t c[3], r[3];
    double h[3];
    for (int k = 0; k < 3; ++k) {
      c[k] = x(v[k]);
      r[k] = y(v[k]);
      h[k] = in_.heightsM[v[k]];
    }
    const std::int64_t c0 = std::min({c[0], c[1], c[2]}), c1 = std::max({c[0], c[1], c[2]});
    const std::int64_t r0 = std::min({r[0], r[1], r[2]}), r1 = std::max({r[0], r[1], r[2]});
    for (std::int64_t row = r0; row <= r1; ++row) {
      for (std::int64_t col = c0; col <= c1; ++col) {
        const std::int64_t b0 = (c[1] - col) * (r[2] - row) - (c[2] - col) * (r[1] - row);
        const std::int64_t b1 = (c[2] - col) * (r[0] - row) - (c[0] - col) * (r[2] - row);
        const std::int64_t b2 = area - b0 - b1;
        if (b0 < 0 || b1 < 0 || b2 < 0) continue;
        const std::size_t s = std::size_t(row) * std::size_t(in_.width) + std::size_t(col);
        const double interpolated =
            (double(b0) * h[0] + double(b1) * h[1] + double(b2) * h[2]) / double(area);
        const double miss = std::abs(interpolated - double(in_.heightsM[s]));
        if (miss > worst.missM) worst = {miss, std::uint32_t(s)};
      }
    }
    return worst;
  }

 private:
  std::uint32_t sampleOf(int col, int row) const {
    return std::uint32_t(row) * std::uint32_t(in_.width) + std::uint32_t(col);
  }
  const GreedyTinInput& in_;
};

// Scattered points in buckets (a coarse grid over their rectangle, about four points a
// bucket); the error is the 3-D distance to the triangle's point at the same coordinates.
class ScatteredPoints {
 public:
  explicit ScatteredPoints(const ScatteredTinInput& in) : in_(in) {
    const std::array<std::uint32_t, 4> c = corners();
    x0_ = in_.x[c[0]];
    y0_ = in_.y[c[0]];
    const std::int64_t width = std::int64_t(in_.x[c[2]]) - x0_ + 1;
    const std::int64_t height = std::int64_t(in_.y[c[2]]) - y0_ + 1;
    const double side = std::sqrt(double(width) * double(height) * 4.0 / double(count() + 1));
    bucketSize_ = std::max<std::int64_t>(1, std::int64_t(std::ceil(side)));
    bucketsX_ = (width + bucketSize_ - 1) / bucketSize_;
    bucketsY_ = (height + bucketSize_ - 1) / bucketSize_;
    // Counting sort of the points by bucket.
    start_.assign(std::size_t(bucketsX_ * bucketsY_ + 1), 0);
    for (std::uint32_t p = 0; p < count(); ++p) ++start_[bucketOf(p) + 1];
    for (std::size_t b = 1; b < start_.size(); ++b) start_[b] += start_[b - 1];
    items_.resize(count());
    std::vector<std::uint32_t> fill(start_.begin(), start_.end() - 1);
    for (std::uint32_t p = 0; p < count(); ++p) items_[fill[bucketOf(p)]++] = p;
  }
  std::size_t count() const { return in_.x.size(); }
  std::int64_t x(std::uint32_t p) const { return in_.x[p]; }
  std::int64_t y(std::uint32_t p) const { return in_.y[p]; }
  double metresPerUnitX() const { return in_.metresPerUnitX; }
  double metresPerUnitY() const { return in_.metresPerUnitY; }
  double maxErrorM() const { return in_.maxErrorM; }
  std::array<std::uint32_t, 4> corners() const { return {0, 1, 2, 3}; }
  std::vector<std::uint32_t> border() const {
    std::vector<std::uint32_t> points;
    for (std::uint32_t p = 4; p < in_.borderCount; ++p) points.push_back(p);
    return points;
  }

  Worst worstIn(const std::uint32_t v[3], std::int64_t area) const {
    Worst worst{0.0, v[0]};
    double worstSquared = 0.0;
    std::int64_t c[3], r[3];
    for (int k = 0; k < 3; ++k) {
      c[k] = x(v[k]);
      r[k] = y(v[k]);
    }
    const glm::dvec3 &p0 = in_.positions[v[0]], &p1 = in_.positions[v[1]], &p2 = in_.positions[v[2]];
    const std::int64_t bx0 = (std::min({c[0], c[1], c[2]}) - x0_) / bucketSize_;
    const std::int64_t bx1 = (std::max({c[0], c[1], c[2]}) - x0_) / bucketSize_;
    const std::int64_t by0 = (std::min({r[0], r[1], r[2]}) - y0_) / bucketSize_;
    const std::int64_t by1 = (std::max({r[0], r[1], r[2]}) - y0_) / bucketSize_;
    for (std::int64_t by = by0; by <= by1; ++by) {
      for (std::int64_t bx = bx0; bx <= bx1; ++bx) {
        const std::size_t b = std::size_t(by * bucketsX_ + bx);
        for (std::uint32_t k = start_[b]; k < start_[b + 1]; ++k) {
          const std::uint32_t p = items_[k];
          const std::int64_t col = x(p), row = y(p);
          const std::int64_t b0 = (c[1] - col) * (r[2] - row) - (c[2] - col) * (r[1] - row);
          const std::int64_t b1 = (c[2] - col) * (r[0] - row) - (c[0] - col) * (r[2] - row);
          const std::int64_t b2 = area - b0 - b1;
          if (b0 < 0 || b1 < 0 || b2 < 0) continue;
          const glm::dvec3 onTriangle =
              (double(b0) * p0 + double(b1) * p1 + double(b2) * p2) / double(area);
          const glm::dvec3 d = in_.positions[p] - onTriangle;
          const double missSquared = d.x * d.x + d.y * d.y + d.z * d.z;
          if (missSquared > worstSquared) {
            worstSquared = missSquared;
            worst.point = p;
          }
        }
      }
    }
    worst.missM = std::sqrt(worstSquared);  // one square root a triangle, not one a point
    return worst;
  }

 private:
  std::size_t bucketOf(std::uint32_t p) const {
    return std::size_t(((y(p) - y0_) / bucketSize_) * bucketsX_ + (x(p) - x0_) / bucketSize_);
  }
  const ScatteredTinInput& in_;
  std::int64_t x0_ = 0, y0_ = 0, bucketSize_ = 1, bucketsX_ = 1, bucketsY_ = 1;
  std::vector<std::uint32_t> start_;  // per bucket: its first entry in items_ (and one past the end)
  std::vector<std::uint32_t> items_;  // point indices, bucket by bucket
};

template <class Points>
class Triangulation {
 public:
  explicit Triangulation(const Points& points) : points_(points) {}

  GreedyTin run() {
    const auto [c00, c10, c11, c01] = points_.corners();
    // Rows run up: (c00, c10, c11) and (c00, c11, c01) are counter-clockwise.
    const std::int32_t t0 = addTriangle(c00, c10, c11);
    const std::int32_t t1 = addTriangle(c11, c01, c00);
    link(3 * t0 + 2, 3 * t1 + 2);  // c11->c00 against c00->c11
    insertBorder();
    rating_ = true;
    for (std::int32_t t = 0; t < triangleCount(); ++t) rate(t);
    while (!queue_.empty()) {
      const auto [error, t] = queue_.top();
      queue_.pop();
      if (error != error_[std::size_t(t)]) continue;  // stale: rated again since
      if (error <= points_.maxErrorM()) break;
      insert(worst_[std::size_t(t)], t);
    }
    GreedyTin tin;
    std::vector<std::uint32_t> vertexOf(points_.count(), std::numeric_limits<std::uint32_t>::max());
    for (const std::uint32_t sample : corners_) {
      if (vertexOf[sample] == std::numeric_limits<std::uint32_t>::max()) {
        vertexOf[sample] = std::uint32_t(tin.vertices.size());
        tin.vertices.push_back(sample);
      }
      tin.triangles.push_back(vertexOf[sample]);
    }
    for (std::int32_t t = 0; t < triangleCount(); ++t) {
      tin.maxErrorM = std::max(tin.maxErrorM, error_[std::size_t(t)]);
    }
    return tin;
  }

 private:
  std::int64_t colOf(std::uint32_t s) const { return points_.x(s); }
  std::int64_t rowOf(std::uint32_t s) const { return points_.y(s); }
  std::int32_t triangleCount() const { return std::int32_t(corners_.size() / 3); }

  // Twice the signed area of (a, b, c) in plane units: > 0 counter-clockwise. Exact.
  std::int64_t orient(std::uint32_t a, std::uint32_t b, std::uint32_t c) const {
    const std::int64_t ax = colOf(a), ay = rowOf(a), bx = colOf(b), by = rowOf(b);
    const std::int64_t cx = colOf(c), cy = rowOf(c);
    return (bx - ax) * (cy - ay) - (by - ay) * (cx - ax);
  }

  // Whether d lies inside the circle through the counter-clockwise a, b, c (ground metres).
  bool inCircle(std::uint32_t a, std::uint32_t b, std::uint32_t c, std::uint32_t d) const {
    auto x = [&](std::uint32_t s) { return double(colOf(s) - colOf(d)) * points_.metresPerUnitX(); };
    auto y = [&](std::uint32_t s) { return double(rowOf(s) - rowOf(d)) * points_.metresPerUnitY(); };
    const double ax = x(a), ay = y(a), bx = x(b), by = y(b), cx = x(c), cy = y(c);
    const double det = (ax * ax + ay * ay) * (bx * cy - cx * by) -
                       (bx * bx + by * by) * (ax * cy - cx * ay) +
                       (cx * cx + cy * cy) * (ax * by - bx * ay);
    return det > 1e-9 * (std::abs(ax) + std::abs(bx) + std::abs(cx) + 1.0);
  }

  std::int32_t addTriangle(std::uint32_t a, std::uint32_t b, std::uint32_t c) {
    corners_.insert(corners_.end(), {a, b, c});
    adjacent_.insert(adjacent_.end(), {kNone, kNone, kNone});
    error_.push_back(0.0);
    worst_.push_back(0);
    return triangleCount() - 1;
  }
  void setTriangle(std::int32_t t, std::uint32_t a, std::uint32_t b, std::uint32_t c) {
    corners_[std::size_t(3 * t)] = a;
    corners_[std::size_t(3 * t + 1)] = b;
    corners_[std::size_t(3 * t + 2)] = c;
  }
  void link(std::int32_t a, std::int32_t b) {
    if (a != kNone) adjacent_[std::size_t(a)] = b;
    if (b != kNone) adjacent_[std::size_t(b)] = a;
  }
  std::uint32_t vertex(std::int32_t halfEdge) const { return corners_[std::size_t(halfEdge)]; }

  // Finds the triangle's worst point and queues it.
  void rate(std::int32_t t) {
    const std::uint32_t v[3] = {vertex(3 * t), vertex(3 * t + 1), vertex(3 * t + 2)};
    const std::int64_t area = orient(v[0], v[1], v[2]);
    const Worst worst = area > 0 ? points_.worstIn(v, area) : Worst{0.0, v[0]};
    error_[std::size_t(t)] = worst.missM;
    worst_[std::size_t(t)] = worst.point;
    if (worst.missM > points_.maxErrorM()) queue_.emplace(worst.missM, t);
  }

  // Inserts sample p, which lies inside triangle t or on one of its edges.
  void insert(std::uint32_t p, std::int32_t t) {
    for (int k = 0; k < 3; ++k) {
      const std::int32_t e = 3 * t + k;
      if (orient(vertex(e), vertex(nextEdge(e)), p) == 0) {
        splitEdge(p, e);
        return;
      }
    }
    splitTriangle(p, t);
  }

  void splitTriangle(std::uint32_t p, std::int32_t t) {
    const std::uint32_t a = vertex(3 * t), b = vertex(3 * t + 1), c = vertex(3 * t + 2);
    const std::int32_t ab = adjacent_[std::size_t(3 * t)], bc = adjacent_[std::size_t(3 * t + 1)];
    const std::int32_t ca = adjacent_[std::size_t(3 * t + 2)];
    // Each new triangle has its outer edge first and p last.
    setTriangle(t, a, b, p);
    const std::int32_t t1 = addTriangle(b, c, p);
    const std::int32_t t2 = addTriangle(c, a, p);
    link(3 * t, ab);
    link(3 * t1, bc);
    link(3 * t2, ca);
    link(3 * t + 1, 3 * t1 + 2);   // b->p / p->b
    link(3 * t1 + 1, 3 * t2 + 2);  // c->p / p->c
    link(3 * t2 + 1, 3 * t + 2);   // a->p / p->a
    for (const std::int32_t n : {t, t1, t2}) legalise(n);
  }

  // p on the edge e = a->b of triangle t = (a, b, c); the triangle across (b, a, d), if any.
  void splitEdge(std::uint32_t p, std::int32_t e) {
    const std::int32_t t = e / 3;
    const std::uint32_t a = vertex(e), b = vertex(nextEdge(e)), c = vertex(previousEdge(e));
    const std::int32_t bc = adjacent_[std::size_t(nextEdge(e))];
    const std::int32_t ca = adjacent_[std::size_t(previousEdge(e))];
    const std::int32_t o = adjacent_[std::size_t(e)];
    setTriangle(t, c, a, p);  // (a, p, c)
    const std::int32_t t1 = addTriangle(b, c, p);  // (p, b, c)
    link(3 * t, ca);
    link(3 * t1, bc);
    link(3 * t + 2, 3 * t1 + 1);  // p->c / c->p
    if (o == kNone) {
      adjacent_[std::size_t(3 * t + 1)] = kNone;   // a->p on the border
      adjacent_[std::size_t(3 * t1 + 2)] = kNone;  // p->b on the border
      legalise(t);
      legalise(t1);
      return;
    }
    const std::int32_t u = o / 3;
    const std::uint32_t d = vertex(previousEdge(o));
    const std::int32_t ad = adjacent_[std::size_t(nextEdge(o))];
    const std::int32_t db = adjacent_[std::size_t(previousEdge(o))];
    setTriangle(u, d, b, p);                       // (b, p, d)
    const std::int32_t u1 = addTriangle(a, d, p);  // (p, a, d)
    link(3 * u, db);
    link(3 * u1, ad);
    link(3 * u + 2, 3 * u1 + 1);   // p->d / d->p
    link(3 * t + 1, 3 * u1 + 2);   // a->p / p->a
    link(3 * t1 + 2, 3 * u + 1);   // p->b / b->p
    for (const std::int32_t n : {t, t1, u, u1}) legalise(n);
  }

  // Triangle t = (x, y, p), p the inserted point: flips x->y while the point across it lies in
  // the circle of (x, y, p), then looks at the two new outer edges; rates what changed.
  void legalise(std::int32_t t) {
    const std::int32_t e = 3 * t;
    const std::int32_t o = adjacent_[std::size_t(e)];
    if (o != kNone) {
      const std::uint32_t x = vertex(e), y = vertex(e + 1), p = vertex(e + 2);
      const std::uint32_t q = vertex(previousEdge(o));
      if (inCircle(x, y, p, q) && orient(x, q, p) > 0 && orient(q, y, p) > 0) {
        const std::int32_t u = o / 3;
        const std::int32_t xq = adjacent_[std::size_t(nextEdge(o))];
        const std::int32_t qy = adjacent_[std::size_t(previousEdge(o))];
        const std::int32_t yp = adjacent_[std::size_t(e + 1)], px = adjacent_[std::size_t(e + 2)];
        setTriangle(t, x, q, p);
        setTriangle(u, q, y, p);
        link(3 * t, xq);
        link(3 * u, qy);
        link(3 * t + 1, 3 * u + 2);  // q->p / p->q
        link(3 * t + 2, px);
        link(3 * u + 1, yp);
        legalise(t);
        legalise(u);
        return;
      }
    }
    if (rating_) rate(t);
  }

  const Points& points_;
  bool rating_ = false;  // off while the border goes in (every triangle is rated after it)
  std::vector<std::uint32_t> corners_;  // three samples a triangle
  std::vector<std::int32_t> adjacent_;  // per half-edge: the opposite half-edge, kNone on borders
  std::vector<double> error_;           // per triangle: its worst sample's miss
  std::vector<std::uint32_t> worst_;    // per triangle: that sample
  std::priority_queue<std::pair<double, std::int32_t>> queue_;

  void insertBorder() {
    // The border points, each on an edge of the current border (found by a scan of the
    // border edges: fine for tiles, quadratic in the side for big grids).
    auto insertOnBorder = [&](std::uint32_t p) {
      for (std::int32_t e = 0; e < std::int32_t(adjacent_.size()); ++e) {
        if (adjacent_[std::size_t(e)] != kNone) continue;
        const std::uint32_t a = vertex(e), b = vertex(nextEdge(e));
        if (orient(a, b, p) != 0) continue;
        const std::int64_t ca = colOf(a), cb = colOf(b), cp = colOf(p);
        const std::int64_t ra = rowOf(a), rb = rowOf(b), rp = rowOf(p);
        if (cp < std::min(ca, cb) || cp > std::max(ca, cb) || rp < std::min(ra, rb) ||
            rp > std::max(ra, rb) || p == a || p == b) {
          continue;
        }
        splitEdge(p, e);
        return;
      }
    };
    for (const std::uint32_t p : points_.border()) insertOnBorder(p);
  }
};

}  // namespace

GreedyTin buildGreedyTin(const GreedyTinInput& input) {
  const GridPoints points(input);
  return Triangulation<GridPoints>(points).run();
}

GreedyTin buildScatteredTin(const ScatteredTinInput& input) {
  const ScatteredPoints points(input);
  return Triangulation<ScatteredPoints>(points).run();
}

}  // namespace tellus
