#include "tellus/lod/stacks/stack_levels.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include <tbb/parallel_for.h>

#include "tellus/lod/stacks/stack_level_error.hpp"

namespace tellus {

double StackLevels::levelBaseM(int k, double cellM) {
  return -0.5 * (std::ldexp(1.0, k) - 1.0) * cellM;
}

Result<StackLevels> StackLevels::build(const std::vector<StackTerrain>& pyramid, double cellM,
                                       const QuadParams& params) {
  if (Status ok = params.check(); !ok) return ok.error();
  if (params.nodeCells % 2 == 0 || params.nodeCells < 9) {
    return makeError("the octree needs an odd node size of at least 9 cells (got {}): nodes "
                     "overlap by one cell and a parent's cells are two of its children's",
                     params.nodeCells);
  }
  if (pyramid.empty()) return makeError("the stack pyramid has no level");
  for (std::size_t k = 1; k < pyramid.size(); ++k) {
    const StackTerrain& fine = pyramid[k - 1];
    const StackTerrain& coarse = pyramid[k];
    if (coarse.width() != (fine.width() + 1) / 2 || coarse.height() != (fine.height() + 1) / 2 ||
        std::abs(coarse.spacingM() - 2.0 * fine.spacingM()) > 1e-9 * coarse.spacingM()) {
      return makeError("stack pyramid level {} is {} x {} at {} m, not half of level {} ({} x {} "
                       "at {} m)", k, coarse.width(), coarse.height(), coarse.spacingM(), k - 1,
                       fine.width(), fine.height(), fine.spacingM());
    }
  }
  StackLevels out;
  out.params_ = params;
  out.cellM_ = cellM;
  out.spacingM_ = pyramid.front().spacingM();
  out.levels_.resize(pyramid.size());
  if (Status ok = out.quantise(pyramid, {}); !ok) return ok.error();
  out.computeErrors(pyramid, {});
  return out;
}

Status StackLevels::rebuild(const std::vector<StackTerrain>& pyramid,
                            const std::vector<StackRegion>& changed) {
  if (pyramid.size() != levels_.size()) {
    return makeError("the edited pyramid has {} levels, not {}", pyramid.size(), levels_.size());
  }
  if (std::all_of(changed.begin(), changed.end(), [](const StackRegion& r) { return r.empty(); })) {
    return {};
  }
  std::vector<StackRegion> regions(levels_.size());
  std::copy_n(changed.begin(), std::min(changed.size(), regions.size()), regions.begin());
  if (Status ok = quantise(pyramid, regions); !ok) return ok;
  computeErrors(pyramid, changed);
  return {};
}

void StackLevels::computeErrors(const std::vector<StackTerrain>& pyramid,
                                const std::vector<StackRegion>& changed) {
  for (std::size_t k = 1; k < levels_.size(); ++k) {
    StackLevel& level = levels_[k];
    const StackLevel& finer = levels_[k - 1];
    const int w = level.stacks.width, h = level.stacks.height;
    const std::size_t columns = std::size_t(w) * std::size_t(h);
    StackRegion region{0, 0, w - 1, h - 1};
    if (level.errorM.size() != columns) {
      level.errorM.assign(columns, 0.0f);
      level.errorLowM.assign(columns, std::numeric_limits<float>::max());
      level.errorHighM.assign(columns, std::numeric_limits<float>::lowest());
    } else if (!changed.empty()) {
      if (k >= changed.size() || changed[k].empty()) continue;
      region = changed[k];
    }
    const float tolerance = 0.5f * float(std::max(level.stacks.spacingM, level.stacks.cellM));
    // What the smoothing keeps of each level's runs (level k's cells are 2^k cellM high).
    const double survivingCells = survivingRunCells(params_);
    const auto minRunM = [&](std::size_t levelIndex) {
      return float(survivingCells * std::ldexp(cellM_, int(levelIndex)));
    };
    const StackTerrain& coarseTerrain = pyramid[k];
    const StackTerrain& fineTerrain = pyramid[k - 1];
    // Rows are terrain rows (0 north); sample y = h - 1 - row.
    tbb::parallel_for(std::max(region.y0, 0), std::min(region.y1, h - 1) + 1, [&](int row) {
      for (int x = std::max(region.x0, 0); x <= std::min(region.x1, w - 1); ++x) {
        const std::span<const StackLayer> coarse = coarseTerrain.column(x, row);
        ColumnError worst;
        for (int dy = 0; dy < 2; ++dy) {
          const int fineRow = 2 * row + dy;
          if (fineRow >= fineTerrain.height()) continue;
          for (int dx = 0; dx < 2; ++dx) {
            const int fx = 2 * x + dx;
            if (fx >= fineTerrain.width()) continue;
            ColumnError e = columnSurfaceError(coarse, fineTerrain.column(fx, fineRow), tolerance,
                                               minRunM(k), minRunM(k - 1));
            if (k > 1) {  // and what the finer level already missed
              const std::size_t c = std::size_t(fx) +
                                    std::size_t(finer.stacks.width) *
                                        std::size_t(finer.stacks.height - 1 - fineRow);
              e.errorM = std::max(e.errorM, finer.errorM[c]);
              e.lowM = std::min(e.lowM, finer.errorLowM[c]);
              e.highM = std::max(e.highM, finer.errorHighM[c]);
            }
            worst.include(e);
          }
        }
        const std::size_t c = std::size_t(x) + std::size_t(w) * std::size_t(h - 1 - row);
        level.errorM[c] = worst.errorM;
        level.errorLowM[c] = worst.lowM;
        level.errorHighM[c] = worst.highM;
      }
    });
  }
}

Status StackLevels::quantise(const std::vector<StackTerrain>& pyramid,
                             const std::vector<StackRegion>& changed) {
  const double cellM = cellM_;
  topM_ = pyramid.front().topM();
  std::vector<Status> errors(pyramid.size());
  std::vector<StackLevel>& levels = levels_;
  tbb::parallel_for(std::size_t(0), pyramid.size(), [&](std::size_t k) {
    if (!changed.empty()) {
      // An edit: the region's columns only.
      if (changed[k].empty()) return;
      errors[k] = levels[k].stacks.replaceRegion(pyramid[k], changed[k]);
      return;
    }
    Result<QuantisedStacks> q = QuantisedStacks::from(pyramid[k], std::ldexp(cellM, int(k)),
                                                      levelBaseM(int(k), cellM));
    if (!q) {
      errors[k] = q.error();
      return;
    }
    levels[k].stacks = std::move(q.value());
    levels[k].stacks.level = int(k);
  });
  for (std::size_t k = 0; k < errors.size(); ++k) {
    if (!errors[k]) return makeError("stack level {}: {}", k, errors[k].error().message);
  }
  // The height ranges, level 0 from its columns, each next level from the 2 x 2 under it
  // (after an edit, over the changed regions only).
  for (std::size_t k = 0; k < levels_.size(); ++k) {
    StackLevel& level = levels_[k];
    const int w = level.stacks.width, h = level.stacks.height;
    const std::size_t columns = std::size_t(w) * std::size_t(h);
    int y0 = 0, y1 = h - 1, x0 = 0, x1 = w - 1;
    if (!changed.empty() && level.lowestBoundaryM.size() == columns) {
      if (changed[k].empty()) continue;
      x0 = changed[k].x0;
      x1 = changed[k].x1;
      y0 = h - 1 - changed[k].y1;  // terrain rows to sample y
      y1 = h - 1 - changed[k].y0;
    } else {
      level.lowestBoundaryM.assign(columns, std::numeric_limits<float>::max());
      level.highestTopM.assign(columns, std::numeric_limits<float>::lowest());
    }
    for (int y = y0; y <= y1; ++y) {
      for (int x = x0; x <= x1; ++x) {
        float& low = level.lowestBoundaryM[std::size_t(x) + std::size_t(w) * std::size_t(y)];
        float& high = level.highestTopM[std::size_t(x) + std::size_t(w) * std::size_t(y)];
        low = std::numeric_limits<float>::max();
        high = std::numeric_limits<float>::lowest();
        if (k == 0) {
          // Sample row y is terrain row height - 1 - y.
          for (const StackLayer& layer : pyramid[0].column(x, h - 1 - y)) {
            low = std::min(low, layer.bottomM > 0.0f ? layer.bottomM : layer.topM);
            high = std::max(high, layer.topM);
          }
          continue;
        }
        const StackLevel& finer = levels_[k - 1];
        const int fw = finer.stacks.width, fh = finer.stacks.height;
        // Coarse sample y covers fine sample rows whose terrain rows are 2 (h-1-y), +1.
        const int fineRow0 = 2 * (h - 1 - y);
        for (int dy = 0; dy < 2; ++dy) {
          const int fineSampleY = fh - 1 - (fineRow0 + dy);
          if (fineSampleY < 0 || fineSampleY >= fh) continue;
          for (int dx = 0; dx < 2; ++dx) {
            const int fx = 2 * x + dx;
            if (fx >= fw) continue;
            const std::size_t c = std::size_t(fx) + std::size_t(fw) * std::size_t(fineSampleY);
            low = std::min(low, finer.lowestBoundaryM[c]);
            high = std::max(high, finer.highestTopM[c]);
          }
        }
      }
    }
  }
  return {};
}

}  // namespace tellus
