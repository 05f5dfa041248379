#include "tellus/lod/stacks/stack_level_error.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

namespace tellus {
namespace {

// A column's surfaces: the bottoms and tops of its solid runs, at most kMax of them (further
// ones are dropped: columns with that many are not seen in practice).
struct Surfaces {
  static constexpr int kMax = 64;
  float heightM[kMax];
  int count = 0;
};

Surfaces surfacesOf(std::span<const StackLayer> column, float minRunM) {
  // The solid runs (layers that touch merged), gaps thinner than minRunM filled.
  struct Run {
    float bottomM, topM;
  };
  std::vector<Run> runs;
  for (const StackLayer& layer : column) {
    if (!runs.empty() && layer.bottomM - runs.back().topM < std::max(minRunM, 1e-6f)) {
      runs.back().topM = std::max(runs.back().topM, layer.topM);
    } else {
      runs.push_back({layer.bottomM, layer.topM});
    }
  }
  Surfaces s;
  for (const Run& run : runs) {
    if (run.topM - run.bottomM < minRunM) continue;  // smoothed away
    if (s.count + 2 > Surfaces::kMax) break;
    s.heightM[s.count++] = run.bottomM;
    s.heightM[s.count++] = run.topM;
  }
  return s;
}

// A column with no surface left has the base, 0, as its only one.
Surfaces orBase(Surfaces s) {
  if (s.count == 0) s.heightM[s.count++] = 0.0f;
  return s;
}

// The one-sided distances from `from`'s surfaces to `to`'s, into `error`.
void oneSided(const Surfaces& from, const Surfaces& to, float toleranceM, ColumnError& error) {
  for (int i = 0; i < from.count; ++i) {
    const float a = from.heightM[i];
    float nearest = to.heightM[0];
    for (int j = 1; j < to.count; ++j) {
      if (std::abs(to.heightM[j] - a) < std::abs(nearest - a)) nearest = to.heightM[j];
    }
    const float d = std::abs(nearest - a);
    error.errorM = std::max(error.errorM, d);
    if (d > toleranceM) {
      error.lowM = std::min({error.lowM, a, nearest});
      error.highM = std::max({error.highM, a, nearest});
    }
  }
}

}  // namespace

void ColumnError::include(const ColumnError& other) {
  errorM = std::max(errorM, other.errorM);
  lowM = std::min(lowM, other.lowM);
  highM = std::max(highM, other.highM);
}

double survivingRunCells(const QuadParams& params) {
  const std::vector<std::uint32_t> taps = params.filterTaps();
  const int r = params.filterRadius;
  double norm = 0.0;
  for (std::uint32_t w : taps) norm += double(w);
  // A run [offset, offset + t) in cell units; cell i's raw density is its overlap with [i, i + 1),
  // a sample's smoothed density the taps over its neighbours (one axis: a slab is as wide as
  // the filter). The run survives when some sample is more than half solid.
  const auto peak = [&](double offset, double t) {
    double best = 0.0;
    const int last = int(std::ceil(offset + t)) + r;
    for (int i = -r - 1; i <= last; ++i) {
      double sum = 0.0;
      for (int k = -r; k <= r; ++k) {
        const double low = std::max(double(i + k), offset), high = std::min(double(i + k + 1), offset + t);
        sum += double(taps[std::size_t(k + r)]) * std::max(0.0, high - low);
      }
      best = std::max(best, sum / norm);
    }
    return best;
  };
  constexpr int kSteps = 64;
  for (int step = 1; step <= kSteps * (2 * r + 2); ++step) {
    const double t = double(step) / kSteps;
    bool everywhere = true;
    for (int o = 0; o < 16 && everywhere; ++o) everywhere = peak(o / 16.0, t) > 0.5;
    if (everywhere) return t;
  }
  return double(2 * r + 2);
}

ColumnError columnSurfaceError(std::span<const StackLayer> coarse, std::span<const StackLayer> fine,
                               float toleranceM, float coarseMinRunM, float fineMinRunM) {
  const Surfaces shown = surfacesOf(coarse, coarseMinRunM), finer = surfacesOf(fine, fineMinRunM);
  ColumnError error;
  if (!coarse.empty() && shown.count == 0 && finer.count > 0) {
    // The smoothing lost every run the coarse column has while the finer one shows some: a
    // hole at any distance (the sky through a thin terrain seen from afar), not a shift.
    error.errorM = kVanishedErrorM;
    error.lowM = *std::min_element(finer.heightM, finer.heightM + finer.count);
    error.highM = *std::max_element(finer.heightM, finer.heightM + finer.count);
    return error;
  }
  const Surfaces a = orBase(shown), b = orBase(finer);
  oneSided(a, b, toleranceM, error);
  oneSided(b, a, toleranceM, error);
  return error;
}

}  // namespace tellus
