#include "tellus/lod/gamer/gamer_refinement.hpp"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>
#include <tbb/parallel_for.h>

namespace tellus::gamer {

float heightAtGrid(const HeightGrid& grid, double x, double y) {
  x = std::clamp(x, 0.0, double(grid.width - 1));
  y = std::clamp(y, 0.0, double(grid.height - 1));
  const int x0 = std::min(int(x), grid.width - 2), y0 = std::min(int(y), grid.height - 2);
  const double fx = x - x0, fy = y - y0;
  const int row0 = grid.height - 1 - y0;  // y north from the south row; row 0 is the north
  const double h00 = grid.at(x0, row0), h10 = grid.at(x0 + 1, row0);
  const double h01 = grid.at(x0, row0 - 1), h11 = grid.at(x0 + 1, row0 - 1);
  return float((h00 * (1.0 - fx) + h10 * fx) * (1.0 - fy) + (h01 * (1.0 - fx) + h11 * fx) * fy);
}

Result<CoarseTerrain> CoarseTerrain::create(const HeightGrid& grid, int maxDepth) {
  if (grid.width < 2 || grid.height < 2) return makeError("GAMeR needs a grid of at least 2 x 2 samples");
  if (maxDepth < 2 || maxDepth > kMaxPatternDepth) {
    return makeError("GAMeR pattern depth {} is outside [2, {}]", maxDepth, kMaxPatternDepth);
  }
  CoarseTerrain t;
  t.grid_ = &grid;
  t.maxDepth_ = maxDepth;
  const int side = 1 << maxDepth;
  t.cellsX_ = (grid.width - 1 + side - 1) / side;
  t.cellsY_ = (grid.height - 1 + side - 1) / side;
  if (t.cellsX_ > 0xffff || t.cellsY_ > 0xffff) {
    return makeError("GAMeR: {} x {} coarse cells of 2^{} samples exceed 65535 a side; use a larger "
                     "pattern depth", t.cellsX_, t.cellsY_, maxDepth);
  }
  const std::size_t depths = std::size_t(maxDepth) + 1;
  t.cellError_.assign(std::size_t(t.cellsX_) * std::size_t(t.cellsY_) * depths, 0.0f);
  t.cellHeights_.assign(std::size_t(t.cellsX_) * std::size_t(t.cellsY_), HeightRange{});
  tbb::parallel_for(0, t.cellsY_, [&](int cy) {
    std::vector<double> corner;
    for (int cx = 0; cx < t.cellsX_; ++cx) {
      const glm::ivec2 a = t.vertexSample(cx, cy), b = t.vertexSample(cx + 1, cy + 1);
      const std::size_t cell = std::size_t(cy) * std::size_t(t.cellsX_) + std::size_t(cx);
      HeightRange range{grid.at(a.x, grid.height - 1 - a.y), grid.at(a.x, grid.height - 1 - a.y)};
      for (int y = a.y; y <= b.y; ++y) {
        for (int x = a.x; x <= b.x; ++x) {
          const float h = grid.at(x, grid.height - 1 - y);
          range.minM = std::min(range.minM, h);
          range.maxM = std::max(range.maxM, h);
        }
      }
      t.cellHeights_[cell] = range;
      for (int d = 0; d <= maxDepth; ++d) {
        // The uniform depth-d sampling: (2^d + 1)^2 points, split along SW-NE like the cell.
        const int n = 1 << d;
        const double stepX = double(b.x - a.x) / n, stepY = double(b.y - a.y) / n;
        corner.assign(std::size_t(n + 1) * std::size_t(n + 1), 0.0);
        for (int j = 0; j <= n; ++j) {
          for (int i = 0; i <= n; ++i) {
            corner[std::size_t(j) * std::size_t(n + 1) + std::size_t(i)] = heightAtGrid(grid, a.x + i * stepX, a.y + j * stepY);
          }
        }
        double worst = 0.0;
        for (int y = a.y; y <= b.y; ++y) {
          const double fy = double(y - a.y) / stepY;
          const int iy = std::min(int(fy), n - 1);
          const double t01 = fy - iy;
          for (int x = a.x; x <= b.x; ++x) {
            const double fx = double(x - a.x) / stepX;
            const int ix = std::min(int(fx), n - 1);
            const double s = fx - ix;
            const auto at = [&](int i, int j) { return corner[std::size_t(iy + j) * std::size_t(n + 1) + std::size_t(ix + i)]; };
            const double h00 = at(0, 0), h10 = at(1, 0), h11 = at(1, 1), h01 = at(0, 1);
            const double interp = s >= t01 ? h00 + s * (h10 - h00) + t01 * (h11 - h10)
                                           : h00 + t01 * (h01 - h00) + s * (h11 - h01);
            worst = std::max(worst, std::abs(double(grid.at(x, grid.height - 1 - y)) - interp));
          }
        }
        t.cellError_[cell * depths + std::size_t(d)] = float(worst);
      }
    }
  });
  // A vertex's error at each depth: the largest among its (up to four) cells, then the largest
  // at that depth or finer (non-increasing: the tag moves a depth at a time with the distance
  // and its morph depth runs continuously).
  t.vertexError_.assign(std::size_t(t.cellsX_ + 1) * std::size_t(t.cellsY_ + 1) * depths, 0.0f);
  for (int j = 0; j <= t.cellsY_; ++j) {
    for (int i = 0; i <= t.cellsX_; ++i) {
      float* out = &t.vertexError_[(std::size_t(j) * std::size_t(t.cellsX_ + 1) + std::size_t(i)) * depths];
      for (int cy = std::max(0, j - 1); cy <= std::min(t.cellsY_ - 1, j); ++cy) {
        for (int cx = std::max(0, i - 1); cx <= std::min(t.cellsX_ - 1, i); ++cx) {
          for (int d = 0; d <= maxDepth; ++d) out[d] = std::max(out[d], t.cellErrorM(cx, cy, d));
        }
      }
      for (int d = maxDepth - 1; d >= 0; --d) out[d] = std::max(out[d], out[d + 1]);
    }
  }
  return t;
}

glm::ivec2 CoarseTerrain::vertexSample(int i, int j) const {
  const int side = 1 << maxDepth_;
  return {std::min(i * side, grid_->width - 1), std::min(j * side, grid_->height - 1)};
}

Aabb CoarseTerrain::cellBounds(int cx, int cy) const {
  const glm::ivec2 a = vertexSample(cx, cy), b = vertexSample(cx + 1, cy + 1);
  const HeightRange& h = cellHeights_[std::size_t(cy) * std::size_t(cellsX_) + std::size_t(cx)];
  return Aabb{{a.x * grid_->spacingXM, a.y * grid_->spacingYM, double(h.minM)},
              {b.x * grid_->spacingXM, b.y * grid_->spacingYM, double(h.maxM)}};
}

std::array<glm::ivec2, 3> CoarseTerrain::corners(int cx, int cy, int half) const {
  const glm::ivec2 sw = vertexSample(cx, cy), ne = vertexSample(cx + 1, cy + 1);
  if (half == 0) return {sw, glm::ivec2(ne.x, sw.y), ne};  // SW, SE, NE
  return {ne, glm::ivec2(sw.x, ne.y), sw};                   // NE, NW, SW
}

double CoarseTerrain::cellRadiusM() const {
  const double side = double(1 << maxDepth_);
  return 0.5 * std::hypot(side * grid_->spacingXM, side * grid_->spacingYM);
}

float morphDepthAt(const float* errorsM, int tag, double scale, double distanceM, float targetPx, float band) {
  if (tag == 0 || !(band > 0.0f)) return float(tag);
  // Depth d meets the target beyond errorsM[d] * scale / targetPx metres. Just beyond where
  // depth tag - 1 stops meeting it, the tag is the first depth with the same error (depths of
  // equal error are skipped together): the morph starts from that one.
  int coarser = tag - 1;
  while (coarser > 0 && errorsM[coarser - 1] == errorsM[coarser]) --coarser;
  const double coarserFrom = double(errorsM[tag - 1]) * scale / double(targetPx);
  const double tagFrom = double(errorsM[tag]) * scale / double(targetPx);
  const double span = double(band) * (coarserFrom - tagFrom);
  if (!(span > 0.0)) return float(tag);
  const double f = std::clamp((coarserFrom - distanceM) / span, 0.0, 1.0);
  return float(double(coarser) + double(tag - coarser) * f);
}

void CoarseTerrain::depthTags(const LodView& view, float targetPx, float morphBand, DepthTags& tags) const {
  const int columns = cellsX_ + 1;
  const std::size_t vertices = std::size_t(columns) * std::size_t(cellsY_ + 1);
  tags.tag.assign(vertices, 0);
  tags.morphDepth.assign(vertices, 0.0f);
  const double radiusM = cellRadiusM();
  const double scale = double(view.exaggeration) * view.pixelsPerRadian;
  const std::size_t depths = std::size_t(maxDepth_) + 1;
  for (int j = 0; j <= cellsY_; ++j) {
    for (int i = 0; i <= cellsX_; ++i) {
      const glm::ivec2 s = vertexSample(i, j);
      const glm::dvec3 p{s.x * grid_->spacingXM, s.y * grid_->spacingYM,
                         double(grid_->at(s.x, grid_->height - 1 - s.y)) * view.exaggeration};
      const double distance = std::max(view.nearM, glm::length(p - view.cameraM) - radiusM);
      const std::size_t v = std::size_t(j) * std::size_t(columns) + std::size_t(i);
      const float* error = &vertexError_[v * depths];
      int tag = maxDepth_;
      for (int d = 0; d < maxDepth_; ++d) {
        if (double(error[d]) * scale / distance <= double(targetPx)) {
          tag = d;
          break;
        }
      }
      tags.tag[v] = std::uint8_t(tag);
      // No geomorph: every vertex at its own sample (the finest sampling).
      tags.morphDepth[v] = morphBand > 0.0f ? morphDepthAt(error, tag, scale, distance, targetPx, morphBand)
                                            : float(maxDepth_);
    }
  }
}

void CoarseTerrain::select(const LodView& view, const GamerSettings& settings, const PatternPool& pool,
                           const DepthTags& tags, Selection& out) const {
  const std::size_t patterns = pool.patterns.size();
  out.firstInstance.assign(patterns, 0);
  out.instanceCount.assign(patterns, 0);
  out.instances.clear();
  out.triangles = 0;
  out.coarseTriangles = 0;
  const int columns = cellsX_ + 1;
  const auto tag = [&](int i, int j) { return int(tags.tag[std::size_t(j) * std::size_t(columns) + std::size_t(i)]); };
  // Morph depths in the GPU's fixed point (an edge's is the larger of its ends').
  const auto morph = [&](int i, int j) {
    return std::uint32_t(std::lround(tags.morphDepth[std::size_t(j) * std::size_t(columns) + std::size_t(i)] * kMorphDepthScale));
  };
  struct Chosen {
    std::uint32_t pattern;
    Instance instance;
  };
  std::vector<Chosen> chosen;
  chosen.reserve(std::size_t(cellsX_) * std::size_t(cellsY_) * 2);
  for (int cy = 0; cy < cellsY_; ++cy) {
    for (int cx = 0; cx < cellsX_; ++cx) {
      if (settings.culling) {
        Aabb box = cellBounds(cx, cy);
        box.min.z *= view.exaggeration;
        box.max.z *= view.exaggeration;
        if (!view.frustum.intersects(Aabb{box.min - view.cameraM, box.max - view.cameraM})) continue;
      }
      const int sw = tag(cx, cy), se = tag(cx + 1, cy), ne = tag(cx + 1, cy + 1), nw = tag(cx, cy + 1);
      const std::uint32_t msw = morph(cx, cy), mse = morph(cx + 1, cy), mne = morph(cx + 1, cy + 1),
                          mnw = morph(cx, cy + 1);
      for (int half = 0; half < 2; ++half) {
        // Corner 1 is the right angle in both halves: (SW, SE, NE) and (NE, NW, SW).
        const int c0 = half == 0 ? sw : ne, c1 = half == 0 ? se : nw, c2 = half == 0 ? ne : sw;
        const std::uint32_t m0 = half == 0 ? msw : mne, m1 = half == 0 ? mse : mnw, m2 = half == 0 ? mne : msw;
        const int d0 = std::max(c0, c1), d1 = std::max(c1, c2), d2 = std::max(c2, c0);
        const int interior = std::min({d0, d1, d2});
        const std::size_t p = pool.patternIndex(d0, d1, d2);
        chosen.push_back({std::uint32_t(p), Instance(std::uint32_t(cx) | (std::uint32_t(cy) << 16),
                                                      std::uint32_t(half) | (std::uint32_t(interior) << 8),
                                                      std::max(m0, m1) | (std::max(m1, m2) << 16), std::max(m2, m0))});
        ++out.instanceCount[p];
        out.triangles += pool.patterns[p].indexCount / 3;
      }
    }
  }
  out.coarseTriangles = std::uint32_t(chosen.size());
  std::uint32_t next = 0;
  for (std::size_t p = 0; p < patterns; ++p) {
    out.firstInstance[p] = next;
    next += out.instanceCount[p];
  }
  out.instances.resize(chosen.size());
  std::vector<std::uint32_t> cursor = out.firstInstance;
  for (const Chosen& c : chosen) out.instances[cursor[c.pattern]++] = c.instance;
}

namespace {

// Grid coordinates of lattice point (a, b) of `n` steps on a coarse triangle with corners `c`:
// exact (integer corners times steps, divided by a power of two).
glm::dvec2 latticePoint(const std::array<glm::ivec2, 3>& c, int n, int a, int b) {
  const glm::ivec2 sum = a * c[0] + b * c[1] + (n - a - b) * c[2];
  return glm::dvec2(sum) / double(n);
}

// The uniform sampling of depth `depth` of a coarse triangle with corners `c` (grid coordinates)
// at its lattice point (a, b) of `n` steps: the grid's height (bilinear) at a point of the
// depth's own lattice, else linear within the depth's triangle around the point (on an edge:
// along the edge, from its lexicographically smaller end).
double samplingHeight(const HeightGrid& grid, const std::array<glm::ivec2, 3>& c, int n, int depth, int a, int b) {
  const int step = n >> depth;
  const auto at = [&](int pa, int pb) {  // the grid at lattice point (pa, pb)
    const glm::dvec2 p = latticePoint(c, n, pa, pb);
    return double(heightAtGrid(grid, p.x, p.y));
  };
  const int cw = n - a - b;
  if (cw == 0 || a == 0 || b == 0) {
    // Edge 0 runs from corner 0 to 1 (c = 0), edge 1 from 1 to 2 (a = 0), edge 2 from 2 to 0.
    const int edge = cw == 0 ? 0 : a == 0 ? 1 : 2;
    glm::ivec2 from = c[std::size_t(edge)], to = c[std::size_t((edge + 1) % 3)];
    int j = edge == 0 ? b : edge == 1 ? cw : a;  // steps from `from`
    if (to.x < from.x || (to.x == from.x && to.y < from.y)) {
      std::swap(from, to);
      j = n - j;
    }
    const auto along = [&](int s) {
      const glm::ivec2 sum = from * n + (to - from) * s;
      return double(heightAtGrid(grid, double(sum.x) / n, double(sum.y) / n));
    };
    if (j % step == 0) return along(j);
    const int j0 = j - j % step;
    const double t = double(j - j0) / step, h0 = along(j0), h1 = along(j0 + step);
    return h0 + (h1 - h0) * t;
  }
  const int a0 = a - a % step, b0 = b - b % step;
  if (a0 == a && b0 == b) return at(a, b);
  const double u = double(a - a0) / step, v = double(b - b0) / step;
  if (u + v <= 1.0) return at(a0, b0) * (1.0 - u - v) + at(a0 + step, b0) * u + at(a0, b0 + step) * v;
  return at(a0 + step, b0 + step) * (u + v - 1.0) + at(a0 + step, b0) * (1.0 - v) + at(a0, b0 + step) * (1.0 - u);
}

}  // namespace

std::vector<glm::vec3> CoarseTerrain::refinedMesh(const PatternPool& pool, const Selection& selection) const {
  std::vector<glm::vec3> out;
  const int n = pool.latticeSteps;
  for (std::size_t p = 0; p < pool.patterns.size(); ++p) {
    const PatternRange& range = pool.patterns[p];
    for (std::uint32_t k = 0; k < selection.instanceCount[p]; ++k) {
      const Instance instance = selection.instances[selection.firstInstance[p] + k];
      const std::array<glm::ivec2, 3> c =
          corners(int(instance.x & 0xffffu), int(instance.x >> 16), int(instance.y & 0xffu));
      for (std::uint32_t i = 0; i < range.indexCount; ++i) {
        const glm::u16vec2 lattice = pool.vertices[pool.indices[range.firstIndex + i]];
        const int a = lattice.x, b = lattice.y;
        const glm::dvec2 point = latticePoint(c, n, a, b);
        out.emplace_back(float(point.x), float(point.y), morphedHeight(instance, n, a, b));
      }
    }
  }
  return out;
}

float CoarseTerrain::morphedHeight(const Instance& instance, int latticeSteps, int a, int b) const {
  const std::array<glm::ivec2, 3> c = corners(int(instance.x & 0xffffu), int(instance.x >> 16), int(instance.y & 0xffu));
  const float d0 = float(instance.z & 0xffffu) / kMorphDepthScale, d1 = float(instance.z >> 16) / kMorphDepthScale;
  const float d2 = float(instance.w) / kMorphDepthScale;
  const int cw = latticeSteps - a - b;
  // On an edge its edge's depth (the neighbour computes the same); inside, the edges' depths
  // blended so that each dominates near its edge.
  const double ab = double(a) * b, bc = double(b) * cw, ca = double(cw) * a;
  const float depth = cw == 0 ? d0 : a == 0 ? d1 : b == 0 ? d2 : float((d0 * ab + d1 * bc + d2 * ca) / (ab + bc + ca));
  const int lower = std::min(int(depth), maxDepth_);
  const float fraction = lower == maxDepth_ ? 0.0f : depth - float(lower);
  const double coarse = samplingHeight(*grid_, c, latticeSteps, lower, a, b);
  if (fraction == 0.0f) return float(coarse);
  const double fine = samplingHeight(*grid_, c, latticeSteps, lower + 1, a, b);
  return float(coarse + (fine - coarse) * double(fraction));
}

}  // namespace tellus::gamer
