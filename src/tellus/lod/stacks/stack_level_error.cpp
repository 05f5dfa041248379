#include "tellus/lod/stacks/stack_level_error.hpp"

#include <algorithm>
#include <cmath>

namespace tellus {
namespace {

// A column's surfaces: the bottoms and tops of its solid runs (layers that touch merged), at
// most kMax of them (further ones are dropped: columns with that many are not seen in practice).
struct Surfaces {
  static constexpr int kMax = 64;
  float heightM[kMax];
  int count = 0;
};

Surfaces surfacesOf(std::span<const StackLayer> column) {
  Surfaces s;
  if (column.empty()) {
    s.heightM[s.count++] = 0.0f;  // the base
    return s;
  }
  float runBottom = column.front().bottomM, runTop = column.front().topM;
  const auto close = [&] {
    if (s.count + 2 > Surfaces::kMax) return;
    s.heightM[s.count++] = runBottom;
    s.heightM[s.count++] = runTop;
  };
  for (std::size_t i = 1; i < column.size(); ++i) {
    if (column[i].bottomM > runTop) {  // air between: a new run
      close();
      runBottom = column[i].bottomM;
    }
    runTop = std::max(runTop, column[i].topM);
  }
  close();
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

ColumnError columnSurfaceError(std::span<const StackLayer> coarse, std::span<const StackLayer> fine,
                               float toleranceM) {
  const Surfaces a = surfacesOf(coarse), b = surfacesOf(fine);
  ColumnError error;
  oneSided(a, b, toleranceM, error);
  oneSided(b, a, toleranceM, error);
  return error;
}

}  // namespace tellus
