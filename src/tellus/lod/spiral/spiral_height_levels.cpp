#include "tellus/lod/spiral/spiral_height_levels.hpp"

#include <algorithm>
#include <cmath>
#include <utility>

#include "tellus/core/geodesy.hpp"
#include "tellus/tiles/global_tiling.hpp"

namespace tellus {
namespace {

std::int64_t wrapColumn(std::int64_t i, std::int64_t total) {
  const std::int64_t r = i % total;
  return r < 0 ? r + total : r;
}

}  // namespace

double SpiralHeightWindow::stepRad() const {
  return GlobalTiling::tileSizeDeg(depth) / tileCells * wgs84::kDegree;
}

std::int64_t SpiralHeightWindow::columnsRoundTheWorld() const {
  return std::int64_t(GlobalTiling::tilesX(depth)) * tileCells;
}

glm::dvec2 SpiralHeightWindow::samplePosition(double latDeg, double lonDeg) const {
  const double step = GlobalTiling::tileSizeDeg(depth) / tileCells;
  return {(lonDeg + 180.0) / step - double(column0), (90.0 - latDeg) / step - double(row0)};
}

int spiralBaseDepth(int tileCells) {
  int depth = 0;
  while (depth < GlobalTiling::kMaxDepth &&
         std::int64_t(GlobalTiling::tilesX(depth + 1)) * tileCells <= kSpiralBaseColumns) {
    ++depth;
  }
  return depth;
}

namespace {

// log2(pi / (cells x spacing)): the depth whose sample spacing equals the vertex spacing.
double wantedDepth(float spacingRad, int tileCells) {
  return std::log2(M_PI / (double(tileCells) * double(spacingRad)));
}

}  // namespace

int spiralLevelDepthFor(float spacingRad, int tileCells, int baseDepth, int finestDepth) {
  if (!(spacingRad > 0.0f)) return finestDepth;
  // pi / 2^d / cells <= spacing  <=>  d >= log2(pi / (cells * spacing)).
  const double wanted = std::ceil(wantedDepth(spacingRad, tileCells));
  return int(std::clamp(wanted, double(baseDepth), double(finestDepth)));
}

namespace {

// spiralCoarserShare for a vertex whose depth (spiralLevelDepthFor's) is already known.
float coarserShareAt(float spacingRad, int tileCells, int depth, int baseDepth) {
  if (!(spacingRad > 0.0f) || depth <= baseDepth) return 0.0f;
  return float(std::clamp(double(depth) - wantedDepth(spacingRad, tileCells), 0.0, 1.0));
}

}  // namespace

float spiralCoarserShare(float spacingRad, int tileCells, int baseDepth, int finestDepth) {
  return coarserShareAt(spacingRad, tileCells,
                        spiralLevelDepthFor(spacingRad, tileCells, baseDepth, finestDepth),
                        baseDepth);
}

SpiralHeightWindow spiralWindowAround(int depth, int tileCells, int samples, double latDeg,
                                      double lonDeg) {
  SpiralHeightWindow window;
  window.depth = depth;
  window.tileCells = tileCells;
  window.columns = window.rows = samples;
  const double step = GlobalTiling::tileSizeDeg(depth) / tileCells;
  const auto centreColumn = std::int64_t(std::llround((lonDeg + 180.0) / step));
  const auto centreRow = std::int64_t(std::llround((90.0 - latDeg) / step));
  window.column0 = centreColumn - samples / 2;
  window.row0 = centreRow - samples / 2;
  return window;
}

SpiralHeightWindow spiralWholeWorld(int depth, int tileCells) {
  SpiralHeightWindow window;
  window.depth = depth;
  window.tileCells = tileCells;
  window.wholeWorld = true;
  window.columns = int(std::int64_t(GlobalTiling::tilesX(depth)) * tileCells) + 1;
  window.rows = int(std::int64_t(GlobalTiling::tilesY(depth)) * tileCells) + 1;
  return window;
}

bool spiralWindowNeedsMove(const SpiralHeightWindow& window, double latDeg, double lonDeg) {
  if (window.wholeWorld) return false;
  const glm::dvec2 at = window.samplePosition(latDeg, lonDeg);
  double dx = at.x - 0.5 * (window.columns - 1);
  const double total = double(window.columnsRoundTheWorld());
  dx -= total * std::round(dx / total);  // the focal point may be a world away in columns
  const double dy = at.y - 0.5 * (window.rows - 1);
  const double limit = window.columns / 8.0;
  return std::abs(dx) > limit || std::abs(dy) > limit;
}

Status readSpiralHeightWindow(const GlobalStore& store, const Geoid* geoid,
                              SpiralHeightWindow& window) {
  if (window.columns < 2 || window.rows < 2) return makeError("a height window needs 2 x 2 samples");
  const std::int64_t total = window.columnsRoundTheWorld();
  const std::int64_t lastRow = std::int64_t(GlobalTiling::tilesY(window.depth)) * window.tileCells;
  const double step = GlobalTiling::tileSizeDeg(window.depth) / window.tileCells;
  window.heights.assign(std::size_t(window.columns) * std::size_t(window.rows), 0.0f);
  // The rows, clamped at the poles (read at least two).
  std::int64_t j0 = std::clamp<std::int64_t>(window.row0, 0, lastRow);
  std::int64_t j1 = std::clamp<std::int64_t>(window.row0 + window.rows - 1, 0, lastRow);
  if (j1 == j0) {
    if (j0 > 0) --j0; else ++j1;
  }
  // Columns in runs of consecutive samples between wraps round the world.
  int x = 0;
  while (x < window.columns) {
    const std::int64_t a = wrapColumn(window.column0 + x, total);
    int length = 1;
    while (x + length < window.columns && a + length < total &&
           wrapColumn(window.column0 + x + length, total) == a + length) {
      ++length;
    }
    std::int64_t i0 = a, i1 = a + length - 1;
    if (i1 == i0) ++i1;  // read at least two (i1 < total: column `total` is 180 degrees)
    // A quarter sample inside each edge: readGlobalRegion snaps outward to exactly these.
    const GeoBounds box{-180.0 + (double(i0) + 0.25) * step, 90.0 - (double(j1) - 0.25) * step,
                        -180.0 + (double(i1) - 0.25) * step, 90.0 - (double(j0) + 0.25) * step};
    Result<HeightGrid> grid = readGlobalRegion(store, window.depth, box);
    if (!grid) return grid.error();
    for (int y = 0; y < window.rows; ++y) {
      const std::int64_t j = std::clamp<std::int64_t>(window.row0 + y, 0, lastRow);
      float* row = window.heights.data() + std::size_t(y) * std::size_t(window.columns);
      for (int k = 0; k < length; ++k) row[x + k] = grid->at(int(a + k - i0), int(j - j0));
    }
    x += length;
  }
  if (geoid) {
    std::vector<double> lats(std::size_t(window.rows)), lons(std::size_t(window.columns));
    for (int y = 0; y < window.rows; ++y) {
      lats[std::size_t(y)] = std::clamp(90.0 - double(window.row0 + y) * step, -90.0, 90.0);
    }
    for (int i = 0; i < window.columns; ++i) {
      lons[std::size_t(i)] = -180.0 + double(wrapColumn(window.column0 + i, total)) * step;
    }
    std::vector<double> undulations(window.heights.size());
    geoid->undulationsM(lats, lons, undulations);
    window.geoidM.resize(undulations.size());
    for (std::size_t k = 0; k < undulations.size(); ++k) {
      window.geoidM[k] = float(undulations[k]);
      window.heights[k] += window.geoidM[k];
    }
  } else {
    window.geoidM.clear();
  }
  return {};
}

float spiralWindowHeight(const SpiralHeightWindow& window, float x, float y) {
  if (window.wholeWorld) {
    const float around = float(window.columns - 1);
    x -= around * std::floor(x / around);
  }
  x = std::clamp(x, 0.0f, float(window.columns - 1));
  y = std::clamp(y, 0.0f, float(window.rows - 1));
  const int x0 = std::min(int(x), window.columns - 2), y0 = std::min(int(y), window.rows - 2);
  const float fx = x - float(x0), fy = y - float(y0);
  const auto at = [&](int i, int j) {
    return window.heights[std::size_t(j) * std::size_t(window.columns) + std::size_t(i)];
  };
  // The cell's two triangles, split along the diagonal from its north-east sample (x0 + 1, y0)
  // to its south-west one (x0, y0 + 1): the store's full-resolution mesh as the reference
  // renderer draws it (HeightGrid::meshHeightAtWorld), not a bilinear patch, which differs from
  // it by up to a quarter of the cell's twist (metres in steep mountains).
  if (fx + fy <= 1.0f) {
    return at(x0, y0) + (at(x0 + 1, y0) - at(x0, y0)) * fx + (at(x0, y0 + 1) - at(x0, y0)) * fy;
  }
  const float h11 = at(x0 + 1, y0 + 1);
  return h11 + (at(x0, y0 + 1) - h11) * (1.0f - fx) + (at(x0 + 1, y0) - h11) * (1.0f - fy);
}

bool spiralWindowHolds(const SpiralHeightWindow& window, float x, float y) {
  if (window.wholeWorld) return true;
  return x >= 1.0f && y >= 1.0f && x <= float(window.columns - 2) &&
         y <= float(window.rows - 2);
}

namespace {

// The window a vertex `move` (x east, y south, radians) from the focal point takes starting at
// `depth`: that depth's if its window holds the vertex, else the deepest coarser one's, else the
// base; and where the vertex lies in its samples.
std::pair<const SpiralHeightWindow*, glm::vec2> windowFrom(const SpiralHeightStack& stack,
                                                          glm::vec2 move, int depth) {
  const SpiralHeightWindow& base = *stack.base;
  for (; depth > base.depth; --depth) {
    const std::size_t i = std::size_t(depth - base.depth - 1);
    const SpiralHeightWindow* level = stack.levels[i];
    if (!level) continue;
    const glm::vec2 here = stack.levelFocal[i] + move / float(level->stepRad());
    if (spiralWindowHolds(*level, here.x, here.y)) return {level, here};
  }
  return {&base, stack.baseFocal + move / float(base.stepRad())};
}

// Height and undulation of `window` at `at`.
glm::vec2 surfaceIn(const SpiralHeightWindow& window, glm::vec2 at) {
  glm::vec2 surface(spiralWindowHeight(window, at.x, at.y), 0.0f);
  if (!window.geoidM.empty()) {
    SpiralHeightWindow geoid;  // the same interpolation over the undulations
    geoid.columns = window.columns;
    geoid.rows = window.rows;
    geoid.wholeWorld = window.wholeWorld;
    geoid.heights = window.geoidM;
    surface.y = spiralWindowHeight(geoid, at.x, at.y);
  }
  return surface;
}

}  // namespace

SpiralHeightLookup spiralLookupHeight(const SpiralHeightStack& stack, glm::vec2 latLonOffset,
                                      float radius, float stepsPerRevolution, bool blendDepths) {
  const SpiralHeightWindow& base = *stack.base;
  const int finest = base.depth + int(stack.levels.size());
  const glm::vec2 move(latLonOffset.y, -latLonOffset.x);  // x east, y south
  const float spacing = radius * 6.2831853f / stepsPerRevolution;
  const int depth = spiralLevelDepthFor(spacing, base.tileCells, base.depth, finest);
  const auto [window, at] = windowFrom(stack, move, depth);
  glm::vec2 surface = surfaceIn(*window, at);
  SpiralHeightLookup lookup;
  lookup.depth = lookup.coarserDepth = window->depth;
  const float share =
      blendDepths ? coarserShareAt(spacing, base.tileCells, depth, base.depth) : 0.0f;
  if (share > 0.0f) {
    const auto [coarser, coarserAt] = windowFrom(stack, move, depth - 1);
    surface += (surfaceIn(*coarser, coarserAt) - surface) * share;  // as spiral_heights.glsl
    lookup.coarserDepth = coarser->depth;
    lookup.coarserShare = share;
  }
  lookup.heightM = surface.x;
  lookup.geoidM = surface.y;
  return lookup;
}

}  // namespace tellus
