#include "tellus/export/greedy_tin.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <queue>
#include <utility>

namespace tellus {
namespace {

constexpr std::int32_t kNone = -1;

std::int32_t nextEdge(std::int32_t e) { return e % 3 == 2 ? e - 2 : e + 1; }
std::int32_t previousEdge(std::int32_t e) { return e % 3 == 0 ? e + 2 : e - 1; }

class Triangulation {
 public:
  explicit Triangulation(const GreedyTinInput& in) : in_(in) {}

  GreedyTin run() {
    const auto corner = [&](int col, int row) { return sampleOf(col, row); };
    const std::uint32_t c00 = corner(0, 0), c10 = corner(in_.width - 1, 0);
    const std::uint32_t c11 = corner(in_.width - 1, in_.height - 1), c01 = corner(0, in_.height - 1);
    // Rows run up: (c00, c10, c11) and (c00, c11, c01) are counter-clockwise.
    const std::int32_t t0 = addTriangle(c00, c10, c11);
    const std::int32_t t1 = addTriangle(c11, c01, c00);
    link(3 * t0 + 2, 3 * t1 + 2);  // c11->c00 against c00->c11
    if (in_.keepBorder) insertBorder();
    rating_ = true;
    for (std::int32_t t = 0; t < triangleCount(); ++t) rate(t);
    while (!queue_.empty()) {
      const auto [error, t] = queue_.top();
      queue_.pop();
      if (error != error_[std::size_t(t)]) continue;  // stale: rated again since
      if (error <= in_.maxErrorM) break;
      insert(worst_[std::size_t(t)], t);
    }
    GreedyTin tin;
    std::vector<std::uint32_t> vertexOf(std::size_t(in_.width) * std::size_t(in_.height),
                                        std::numeric_limits<std::uint32_t>::max());
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
  std::uint32_t sampleOf(int col, int row) const {
    return std::uint32_t(row) * std::uint32_t(in_.width) + std::uint32_t(col);
  }
  int colOf(std::uint32_t s) const { return int(s % std::uint32_t(in_.width)); }
  int rowOf(std::uint32_t s) const { return int(s / std::uint32_t(in_.width)); }
  std::int32_t triangleCount() const { return std::int32_t(corners_.size() / 3); }

  // Twice the signed area of (a, b, c) in sample units: > 0 counter-clockwise. Exact.
  std::int64_t orient(std::uint32_t a, std::uint32_t b, std::uint32_t c) const {
    const std::int64_t ax = colOf(a), ay = rowOf(a), bx = colOf(b), by = rowOf(b);
    const std::int64_t cx = colOf(c), cy = rowOf(c);
    return (bx - ax) * (cy - ay) - (by - ay) * (cx - ax);
  }

  // Whether d lies inside the circle through the counter-clockwise a, b, c (ground metres).
  bool inCircle(std::uint32_t a, std::uint32_t b, std::uint32_t c, std::uint32_t d) const {
    auto x = [&](std::uint32_t s) { return (colOf(s) - colOf(d)) * in_.spacingXM; };
    auto y = [&](std::uint32_t s) { return (rowOf(s) - rowOf(d)) * in_.spacingYM; };
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

  // Finds the triangle's worst sample and queues it.
  void rate(std::int32_t t) {
    const std::uint32_t v[3] = {vertex(3 * t), vertex(3 * t + 1), vertex(3 * t + 2)};
    const std::int64_t area = orient(v[0], v[1], v[2]);
    double worst = 0.0;
    std::uint32_t worstSample = v[0];
    if (area > 0) {
      std::int64_t c[3], r[3];
      double h[3];
      for (int k = 0; k < 3; ++k) {
        c[k] = colOf(v[k]);
        r[k] = rowOf(v[k]);
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
          if (miss > worst) {
            worst = miss;
            worstSample = std::uint32_t(s);
          }
        }
      }
    }
    error_[std::size_t(t)] = worst;
    worst_[std::size_t(t)] = worstSample;
    if (worst > in_.maxErrorM) queue_.emplace(worst, t);
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

  const GreedyTinInput& in_;
  bool rating_ = false;  // off while the border goes in (every triangle is rated after it)
  std::vector<std::uint32_t> corners_;  // three samples a triangle
  std::vector<std::int32_t> adjacent_;  // per half-edge: the opposite half-edge, kNone on borders
  std::vector<double> error_;           // per triangle: its worst sample's miss
  std::vector<std::uint32_t> worst_;    // per triangle: that sample
  std::priority_queue<std::pair<double, std::int32_t>> queue_;

  void insertBorder() {
    // The border samples, each on an edge of the current border (found by a scan of the
    // border edges: fine for tiles, quadratic in the side for big grids).
    auto insertOnBorder = [&](std::uint32_t p) {
      for (std::int32_t e = 0; e < std::int32_t(adjacent_.size()); ++e) {
        if (adjacent_[std::size_t(e)] != kNone) continue;
        const std::uint32_t a = vertex(e), b = vertex(nextEdge(e));
        if (orient(a, b, p) != 0) continue;
        const int ca = colOf(a), cb = colOf(b), cp = colOf(p);
        const int ra = rowOf(a), rb = rowOf(b), rp = rowOf(p);
        if (cp < std::min(ca, cb) || cp > std::max(ca, cb) || rp < std::min(ra, rb) ||
            rp > std::max(ra, rb) || p == a || p == b) {
          continue;
        }
        splitEdge(p, e);
        return;
      }
    };
    for (int col = 1; col + 1 < in_.width; ++col) {
      insertOnBorder(sampleOf(col, 0));
      insertOnBorder(sampleOf(col, in_.height - 1));
    }
    for (int row = 1; row + 1 < in_.height; ++row) {
      insertOnBorder(sampleOf(0, row));
      insertOnBorder(sampleOf(in_.width - 1, row));
    }
  }
};

}  // namespace

GreedyTin buildGreedyTin(const GreedyTinInput& input) { return Triangulation(input).run(); }

}  // namespace tellus
