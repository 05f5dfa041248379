#include "tellus/lod/clipmaps/clipmap_prefilter.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <utility>

namespace tellus::clipmaps {
namespace {

constexpr int kR = PrefilterKernel::kRadius;
constexpr int kSide = PrefilterKernel::kSide;

// A square grid of doubles, row by row.
struct Grid {
  int side = 0;
  std::vector<double> values;
  explicit Grid(int s) : side(s), values(std::size_t(s) * std::size_t(s), 0.0) {}
  double& at(int x, int y) { return values[std::size_t(y) * std::size_t(side) + std::size_t(x)]; }
  double at(int x, int y) const { return values[std::size_t(y) * std::size_t(side) + std::size_t(x)]; }
};

// P: a coarse grid's surface (SW-NE triangles; row grows southwards) at the finer grid's
// samples. The finer grid has 2 side - 1 samples a side.
Grid interpolate(const Grid& coarse) {
  Grid fine(2 * coarse.side - 1);
  for (int y = 0; y < fine.side; ++y) {
    for (int x = 0; x < fine.side; ++x) {
      const int i = x / 2, j = y / 2;
      const bool oddX = (x & 1) != 0, oddY = (y & 1) != 0;
      double v = coarse.at(i, j);
      if (oddX && !oddY) v = 0.5 * (coarse.at(i, j) + coarse.at(i + 1, j));
      if (!oddX && oddY) v = 0.5 * (coarse.at(i, j) + coarse.at(i, j + 1));
      if (oddX && oddY) v = 0.5 * (coarse.at(i, j + 1) + coarse.at(i + 1, j));  // SW and NE
      fine.at(x, y) = v;
    }
  }
  return fine;
}

// P^T: the transpose of interpolate().
Grid interpolateTransposed(const Grid& fine) {
  Grid coarse((fine.side + 1) / 2);
  for (int y = 0; y < fine.side; ++y) {
    for (int x = 0; x < fine.side; ++x) {
      const int i = x / 2, j = y / 2;
      const bool oddX = (x & 1) != 0, oddY = (y & 1) != 0;
      const double v = fine.at(x, y);
      if (!oddX && !oddY) {
        coarse.at(i, j) += v;
      } else if (oddX && !oddY) {
        coarse.at(i, j) += 0.5 * v;
        coarse.at(i + 1, j) += 0.5 * v;
      } else if (!oddX && oddY) {
        coarse.at(i, j) += 0.5 * v;
        coarse.at(i, j + 1) += 0.5 * v;
      } else {
        coarse.at(i, j + 1) += 0.5 * v;
        coarse.at(i + 1, j) += 0.5 * v;
      }
    }
  }
  return coarse;
}

double dot(const Grid& a, const Grid& b) {
  double sum = 0.0;
  for (std::size_t k = 0; k < a.values.size(); ++k) sum += a.values[k] * b.values[k];
  return sum;
}

// The least-squares fit's weights: coarse sample c of the fit is row c of (P^T P)^-1 P^T, that
// is (P x)^T with (P^T P) x = e_c; read around c's position on a grid wide enough for the
// weights to have died out at its edges.
PrefilterKernel computeKernel() {
  constexpr int kCoarseSide = 33, kCentre = 16;
  Grid b(kCoarseSide);
  b.at(kCentre, kCentre) = 1.0;
  Grid x(kCoarseSide), r = b, p = b;
  double rr = dot(r, r);
  for (int iteration = 0; iteration < 500 && rr > 1e-24; ++iteration) {
    const Grid ap = interpolateTransposed(interpolate(p));
    const double alpha = rr / dot(p, ap);
    for (std::size_t k = 0; k < x.values.size(); ++k) {
      x.values[k] += alpha * p.values[k];
      r.values[k] -= alpha * ap.values[k];
    }
    const double next = dot(r, r);
    for (std::size_t k = 0; k < p.values.size(); ++k) p.values[k] = r.values[k] + next / rr * p.values[k];
    rr = next;
  }
  const Grid row = interpolate(x);
  double sum = 0.0;
  for (int dy = -kR; dy <= kR; ++dy) {
    for (int dx = -kR; dx <= kR; ++dx) sum += row.at(2 * kCentre + dx, 2 * kCentre + dy);
  }
  PrefilterKernel kernel;
  for (int dy = -kR; dy <= kR; ++dy) {
    for (int dx = -kR; dx <= kR; ++dx) {
      kernel.weights[std::size_t((dy + kR) * kSide + dx + kR)] = float(row.at(2 * kCentre + dx, 2 * kCentre + dy) / sum);
    }
  }
  return kernel;
}

// The one expression both paths use, so that they agree bit for bit: the weighted sum of the
// finer samples finer(dx, dy) around a coarse sample, clamped to the terrain's range.
template <typename Finer>
float convolve(const LevelFilter& filter, const Finer& finer) {
  const PrefilterKernel& kernel = leastSquaresKernel();
  // One sum a row, then the rows in order: independent chains of additions the CPU overlaps.
  std::array<double, kSide> rows{};
  for (int dx = -kR; dx <= kR; ++dx) {
    for (int dy = -kR; dy <= kR; ++dy) {
      rows[std::size_t(dy + kR)] += double(kernel.weights[std::size_t((dy + kR) * kSide + dx + kR)]) * double(finer(dx, dy));
    }
  }
  double sum = 0.0;
  for (const double row : rows) sum += row;
  return std::clamp(float(sum), filter.minHeightM, filter.maxHeightM);
}

// Whether the window of level `level`'s sample `sample` (level - 1 samples 2 sample +- R) lies
// inside the data, so that no clamped sample enters the sum.
bool windowInsideData(const LevelFilter& filter, int level, glm::ivec2 sample) {
  if (filter.dataSize.x <= 0 || filter.dataSize.y <= 0) return true;
  const glm::ivec2 last((filter.dataSize.x - 1) >> (level - 1), (filter.dataSize.y - 1) >> (level - 1));
  const glm::ivec2 low = 2 * sample - kR, high = 2 * sample + kR;
  return low.x >= 0 && low.y >= 0 && high.x <= last.x && high.y <= last.y;
}

}  // namespace

const PrefilterKernel& leastSquaresKernel() {
  static const PrefilterKernel kernel = computeKernel();
  return kernel;
}

float filteredHeight(const LevelSampler& stored, const LevelFilter& filter, int level, glm::ivec2 sample) {
  if (level == 0 || !filter.prefilter || !windowInsideData(filter, level, sample)) return stored(level, sample);
  return convolve(filter, [&](int dx, int dy) { return stored(level - 1, 2 * sample + glm::ivec2(dx, dy)); });
}

LevelSampler filteredSampler(LevelSampler stored, LevelFilter filter) {
  return [stored = std::move(stored), filter](int level, glm::ivec2 sample) {
    return filteredHeight(stored, filter, level, sample);
  };
}

std::vector<float> filteredBlock(const LevelSampler& stored, const LevelFilter& filter, int level, const SampleRect& rect) {
  std::vector<float> out;
  if (rect.empty()) return out;
  const glm::ivec2 size = rect.max - rect.min;
  out.reserve(std::size_t(size.x) * std::size_t(size.y));
  if (level == 0 || !filter.prefilter) {
    for (int y = rect.min.y; y < rect.max.y; ++y) {
      for (int x = rect.min.x; x < rect.max.x; ++x) out.push_back(stored(level, {x, y}));
    }
    return out;
  }
  // The finer samples every output reads: [2 min - R, 2 (max - 1) + R] per axis.
  const glm::ivec2 first = 2 * rect.min - kR;
  const glm::ivec2 side = 2 * (size - 1) + kSide;
  std::vector<float> finer(std::size_t(side.x) * std::size_t(side.y));
  for (int y = 0; y < side.y; ++y) {
    for (int x = 0; x < side.x; ++x) finer[std::size_t(y) * std::size_t(side.x) + std::size_t(x)] = stored(level - 1, first + glm::ivec2(x, y));
  }
  for (int y = 0; y < size.y; ++y) {
    for (int x = 0; x < size.x; ++x) {
      const glm::ivec2 sample = rect.min + glm::ivec2(x, y);
      if (!windowInsideData(filter, level, sample)) {
        out.push_back(stored(level, sample));
        continue;
      }
      out.push_back(convolve(filter, [&](int dx, int dy) {
        return finer[std::size_t(2 * y + kR + dy) * std::size_t(side.x) + std::size_t(2 * x + kR + dx)];
      }));
    }
  }
  return out;
}

}  // namespace tellus::clipmaps
