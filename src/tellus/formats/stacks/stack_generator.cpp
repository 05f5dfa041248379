#include "tellus/formats/stacks/stack_generator.hpp"

#include <array>
#include <algorithm>
#include <cmath>
#include <limits>
#include <queue>
#include <random>

#include <spdlog/spdlog.h>
#include <tbb/parallel_for.h>

#include "tellus/dem/gradient_noise.hpp"

namespace tellus {
namespace {

constexpr float kSliverM = 0.01f;  // thinner pieces are dropped

using Column = std::vector<StackLayer>;

// Removes [bottom, top) from the column's layers.
void carve(Column& column, float bottom, float top) {
  Column out;
  for (const StackLayer& l : column) {
    if (l.topM <= bottom || l.bottomM >= top) {
      out.push_back(l);
      continue;
    }
    if (l.bottomM < bottom - kSliverM) out.push_back({l.bottomM, bottom, l.material});
    if (l.topM > top + kSliverM) out.push_back({top, l.topM, l.material});
  }
  column = std::move(out);
}

// Fills the air of [bottom, top) with `material`, leaving what is there.
void addSolid(Column& column, float bottom, float top, StackMaterial material) {
  if (!(top > bottom + kSliverM)) return;
  Column out;
  float from = bottom;
  for (const StackLayer& l : column) {
    if (l.bottomM > from + kSliverM && from < top) out.push_back({from, std::min(l.bottomM, top), material});
    out.push_back(l);
    from = std::max(from, l.topM);
  }
  if (top > from + kSliverM) out.push_back({from, top, material});
  // Adjacent pieces of one material become one layer.
  Column merged;
  for (const StackLayer& l : out) {
    if (!merged.empty() && merged.back().material == l.material && merged.back().topM >= l.bottomM) {
      merged.back().topM = std::max(merged.back().topM, l.topM);
    } else {
      merged.push_back(l);
    }
  }
  column = std::move(merged);
}

float groundOf(const Column& column) { return column.empty() ? 0.0f : column.back().topM; }

}  // namespace

HeightGrid squareCells(const HeightGrid& grid) {
  if (std::abs(grid.spacingYM - grid.spacingXM) <= 0.01 * grid.spacingXM) return grid;
  const double cell = std::min(grid.spacingXM, grid.spacingYM);
  const int w = std::max(2, int(std::floor(double(grid.width - 1) * grid.spacingXM / cell)) + 1);
  const int h = std::max(2, int(std::floor(double(grid.height - 1) * grid.spacingYM / cell)) + 1);
  HeightGrid out(w, h);
  out.spacingXM = out.spacingYM = cell;
  out.georef = grid.georef;
  // Output sample x lies on input sample x * sx (sample centres at pixel + 1/2): pixel X of the
  // output is pixel sx * (X - 1/2) + 1/2 of the input, and the same in y.
  const double sx = cell / grid.spacingXM, sy = cell / grid.spacingYM;
  const std::array<double, 6>& g = grid.georef.geoTransform;
  out.georef.geoTransform = {g[0] + 0.5 * (1.0 - sx) * g[1] + 0.5 * (1.0 - sy) * g[2], sx * g[1], sy * g[2],
                             g[3] + 0.5 * (1.0 - sx) * g[4] + 0.5 * (1.0 - sy) * g[5], sx * g[4], sy * g[5]};
  for (int y = 0; y < h; ++y) {
    const double fy = std::min(double(y) * cell / grid.spacingYM, double(grid.height - 1));
    const int y0 = std::min(int(fy), grid.height - 2);
    for (int x = 0; x < w; ++x) {
      const double fx = std::min(double(x) * cell / grid.spacingXM, double(grid.width - 1));
      const int x0 = std::min(int(fx), grid.width - 2);
      const double tx = fx - x0, ty = fy - y0;
      const double top = grid.at(x0, y0) * (1 - tx) + grid.at(x0 + 1, y0) * tx;
      const double bottom = grid.at(x0, y0 + 1) * (1 - tx) + grid.at(x0 + 1, y0 + 1) * tx;
      out.at(x, y) = float(top * (1 - ty) + bottom * ty);
    }
  }
  return out;
}

std::size_t removeFloatingLayers(int width, int height, std::vector<Column>& columns) {
  // Layer ids: column c's layer i is first[c] + i.
  std::vector<std::size_t> first(columns.size() + 1, 0);
  for (std::size_t c = 0; c < columns.size(); ++c) first[c + 1] = first[c] + columns[c].size();
  std::vector<char> joined(first.back(), 0);
  std::queue<std::pair<std::size_t, std::size_t>> todo;  // (column, layer)
  for (std::size_t c = 0; c < columns.size(); ++c) {
    if (!columns[c].empty() && columns[c][0].bottomM <= 0.0f) {
      joined[first[c]] = 1;
      todo.push({c, 0});
    }
  }
  const auto visit = [&](std::size_t c, std::size_t i) {
    if (!joined[first[c] + i]) {
      joined[first[c] + i] = 1;
      todo.push({c, i});
    }
  };
  while (!todo.empty()) {
    const auto [c, i] = todo.front();
    todo.pop();
    const StackLayer& l = columns[c][i];
    // In the column: layers that touch.
    if (i > 0 && columns[c][i - 1].topM >= l.bottomM) visit(c, i - 1);
    if (i + 1 < columns[c].size() && columns[c][i + 1].bottomM <= l.topM) visit(c, i + 1);
    // Across each side: layers overlapping it in height.
    const int x = int(c % std::size_t(width)), y = int(c / std::size_t(width));
    const int dx[4] = {1, -1, 0, 0}, dy[4] = {0, 0, 1, -1};
    for (int k = 0; k < 4; ++k) {
      const int nx = x + dx[k], ny = y + dy[k];
      if (nx < 0 || ny < 0 || nx >= width || ny >= height) continue;
      const std::size_t n = std::size_t(ny) * std::size_t(width) + std::size_t(nx);
      for (std::size_t j = 0; j < columns[n].size(); ++j) {
        const StackLayer& m = columns[n][j];
        if (m.bottomM < l.topM && m.topM > l.bottomM) visit(n, j);
      }
    }
  }
  std::size_t removed = 0;
  for (std::size_t c = 0; c < columns.size(); ++c) {
    Column kept;
    for (std::size_t i = 0; i < columns[c].size(); ++i) {
      if (joined[first[c] + i]) {
        kept.push_back(columns[c][i]);
      } else {
        ++removed;
      }
    }
    columns[c] = std::move(kept);
  }
  return removed;
}

Result<StackTerrain> generateStacks(const HeightGrid& grid, const StackGeneratorOptions& options,
                                    StackFeatureReport* report) {
  if (grid.width < 2 || grid.height < 2 || grid.heights.empty()) {
    return makeError("stacks: the DEM has {} x {} samples; at least 2 x 2 are needed", grid.width,
                     grid.height);
  }
  const double spacing = grid.spacingXM;
  if (!(spacing > 0.0) || std::abs(grid.spacingYM - spacing) > 0.01 * spacing) {
    return makeError("stacks: the DEM's samples are {} x {} m apart; stacks need square cells "
                     "(reproject or resample it first)",
                     grid.spacingXM, grid.spacingYM);
  }
  const int w = grid.width, h = grid.height;
  if (options.features.caves) {
    // The cave pass samples two 3D noises every min(spacing, 1 m) over caveDepthM in every
    // column: refused before it starts when that cannot finish in minutes.
    const double cell = std::min(spacing, 1.0);
    const double samples = double(w) * double(h) * (options.caveDepthM + 1.0) / cell;
    if (samples > kMaxCaveSamples) {
      const double finest = double(w) * double(h) * (options.caveDepthM + 1.0) / kMaxCaveSamples;
      return makeError("stacks: {} x {} stacks at {:.3g} m would carve caves in {:.3g} cells of "
                       "{:.3g} m ({:.0f} m deep under every stack), more than the {:.0e} that "
                       "finish in minutes; give a --spacing of at least {:.3g} m, or --features "
                       "without caves",
                       w, h, spacing, samples, cell, options.caveDepthM, kMaxCaveSamples, finest);
    }
  }
  const float lowest = *std::min_element(grid.heights.begin(), grid.heights.end());
  // Room for caves under the lowest ground.
  const float base =
      std::floor(lowest) - 8.0f - (options.features.caves ? float(options.caveDepthM) : 0.0f);
  const auto ground = [&](int x, int y) {
    return grid.at(std::clamp(x, 0, w - 1), std::clamp(y, 0, h - 1)) - base;
  };
  std::vector<Column> columns(std::size_t(w) * std::size_t(h));
  const auto index = [w](int x, int y) { return std::size_t(y) * std::size_t(w) + std::size_t(x); };

  // The heightfield: rock, soil thinning with the slope, grass on the soil.
  tbb::parallel_for(0, h, [&](int y) {
    for (int x = 0; x < w; ++x) {
      const float g = ground(x, y);
      const double sx = (ground(x + 1, y) - ground(x - 1, y)) / (2.0 * spacing);
      const double sy = (ground(x, y + 1) - ground(x, y - 1)) / (2.0 * spacing);
      const double slope = std::sqrt(sx * sx + sy * sy);  // 1 = 45 degrees
      const auto soil = float(options.soilDepthM * std::clamp(1.0 - slope, 0.0, 1.0));
      const auto grass = std::min(soil, float(options.grassDepthM));
      Column& c = columns[index(x, y)];
      c.push_back({0.0f, g - soil, kStackRock});
      if (soil - grass > kSliverM) c.push_back({g - soil, g - grass, kStackSoil});
      if (grass > kSliverM) c.push_back({g - grass, g, kStackGrass});
    }
  });

  // Overhangs: over the foot of a cliff (a side dropping more than three stacks' spacing), a
  // lip of rock from the cliff's top reaches out up to five stacks, thinning from 3 m (or 2.5
  // stacks) to 60 % of that, so that it stays thicker than the smoothing's reach at the
  // pipeline's cells (a thinner lip would melt into the cliff); it ends where it would come
  // within two stacks of the ground below. Only where a 2D noise says so, so some cliffs have
  // lips and others not.
  if (options.features.overhangs) {
    const GradientNoise lips(options.seed ^ 0x0f0e0d0cULL);
    const int dx[4] = {1, -1, 0, 0}, dy[4] = {0, 0, 1, -1};
    const auto thick = float(std::max(3.0, 2.5 * spacing));
    std::vector<std::tuple<std::size_t, float, float>> adds;
    for (int y = 0; y < h; ++y) {
      for (int x = 0; x < w; ++x) {
        const float top = ground(x, y);
        if (lips.sample(glm::dvec2(x, y) * (spacing / 60.0)).x < 0.12) continue;
        for (int k = 0; k < 4; ++k) {
          const int nx = x + dx[k], ny = y + dy[k];
          if (nx < 0 || ny < 0 || nx >= w || ny >= h) continue;
          if (top - ground(nx, ny) < 3.0 * spacing) continue;
          for (int step = 1; step <= 5; ++step) {
            const int lx = x + dx[k] * step, ly = y + dy[k] * step;
            if (lx < 0 || ly < 0 || lx >= w || ly >= h) break;
            const float t = thick * (1.0f - 0.1f * float(step - 1));
            if (top - t <= ground(lx, ly) + 2.0f * float(spacing)) break;  // too near the ground
            adds.emplace_back(index(lx, ly), top - t, top - 0.1f * float(step));
          }
        }
      }
    }
    for (const auto& [c, b, t] : adds) addSolid(columns[c], b, t, kStackRock);
  }

  // Arches: in every region of 256 x 256 stacks, the best of 400 random spans: from a point,
  // a walk of 6 to 48 stacks (or 240 m on fine grids) across a valley to ground as high again
  // (within 4 m); the opening under a straight deck between the two ends must be 8 m tall at
  // least and a twentieth of the span, and the best (tall openings, short spans) is built: a
  // deck 4 m (or 2.5 stacks) thick on legs (see below).
  if (options.features.arches) {
    std::mt19937_64 random(options.seed * 0x9E3779B97F4A7C15ULL + 17);
    // 4 m, or two and a half stacks on coarse grids, where a thinner deck would vanish at the
    // pipeline's density resolution (one cell a stack).
    const auto deckM = float(std::max(4.0, 2.5 * spacing));
    const int longest = std::max(48, int(240.0 / spacing));  // stacks
    struct Span {
      int x0 = 0, y0 = 0, end = 0;
      double ux = 0, uy = 0;
      float clearance = -1.0f;
    };
    const auto along = [](int origin, double u, int s) { return origin + int(std::lround(u * s)); };
    for (int ry = 0; ry < (h + 255) / 256; ++ry) {
      for (int rx = 0; rx < (w + 255) / 256; ++rx) {
        const int rw = std::min(256, w - rx * 256), rh = std::min(256, h - ry * 256);
        Span best;
        for (int attempt = 0; attempt < 400; ++attempt) {
          Span span;
          span.x0 = rx * 256 + int(random() % std::uint64_t(rw));
          span.y0 = ry * 256 + int(random() % std::uint64_t(rh));
          const double angle = double(random() % 16) * (6.283185307179586 / 16.0);
          span.ux = std::cos(angle);
          span.uy = std::sin(angle);
          const float g0 = ground(span.x0, span.y0);
          for (int s = 1; s <= longest; ++s) {
            const int x = along(span.x0, span.ux, s), y = along(span.y0, span.uy, s);
            if (x < 1 || y < 1 || x >= w - 1 || y >= h - 1) break;
            if (s >= 6 && ground(x, y) >= g0 - 4.0f) {
              span.end = s;
              break;
            }
          }
          if (span.end == 0) continue;
          const float g1 = ground(along(span.x0, span.ux, span.end), along(span.y0, span.uy, span.end));
          span.clearance = 0.0f;  // the opening's height: the deepest point under the deck
          for (int s = 1; s < span.end; ++s) {
            const float deck = g0 + (g1 - g0) * float(s) / float(span.end);
            span.clearance = std::max(span.clearance, deck - deckM - ground(along(span.x0, span.ux, s),
                                                                           along(span.y0, span.uy, s)));
          }
          // Tall openings over short spans look like arches; long low ones like bridges.
          const auto score = [spacing](const Span& a) {
            return a.clearance - float(a.end * spacing) / 8.0f;
          };
          if (span.clearance >= 8.0f && span.clearance * 20.0f >= float(span.end * spacing) &&
              (best.clearance < 0.0f || score(span) > score(best))) {
            best = span;
          }
        }
        if (best.clearance < 0.0f) continue;  // none found
        const float g0 = ground(best.x0, best.y0);
        const float g1 = ground(along(best.x0, best.ux, best.end), along(best.y0, best.uy, best.end));
        // The arch's shape: the deck's top straight between the two ends; its underside an arc,
        // the rock reaching down to the ground at the ends (the legs, f = 1) and the deck alone
        // at the middle (f = 0); a rounded cross-section, a tenth of the span wide (3 to 12
        // stacks). Stacks are filled half a step apart along and across so no column is missed.
        const int halfWidth = std::clamp(best.end / 20, 1, 6);
        for (int half = 0; half <= 2 * best.end; ++half) {
          const double t = double(half) / double(2 * best.end);
          const float top = g0 + (g1 - g0) * float(t);
          const float legs = float(std::pow(1.0 - std::sin(3.141592653589793 * t), 1.5));
          for (int side = -2 * halfWidth; side <= 2 * halfWidth; ++side) {
            const double across = 0.5 * side;
            const int x = int(std::lround(best.x0 + best.ux * t * best.end - best.uy * across));
            const int y = int(std::lround(best.y0 + best.uy * t * best.end + best.ux * across));
            if (x < 0 || y < 0 || x >= w || y >= h) continue;
            const auto round = float(std::sqrt(std::max(0.0, 1.0 - std::pow(across / (halfWidth + 0.5), 2.0))));
            const float thickness = deckM * (0.4f + 0.6f * round);
            const float deckTop = top - 0.5f * deckM * (1.0f - round);
            const float deckBottom = deckTop - thickness;
            const float bottom = deckBottom - legs * std::max(0.0f, deckBottom - ground(x, y));
            addSolid(columns[index(x, y)], std::max(bottom, 0.0f), deckTop, kStackRock);
          }
        }
        if (report) {
          report->arches.push_back({best.x0, best.y0, along(best.x0, best.ux, best.end),
                                    along(best.y0, best.uy, best.end), g0, g1, best.clearance});
        }
        spdlog::debug("arch from stack ({}, {}) to ({}, {}), deck {:.1f} to {:.1f} m, {:.1f} m clear",
                      best.x0, best.y0, along(best.x0, best.ux, best.end),
                      along(best.y0, best.uy, best.end), g0, g1, best.clearance);
      }
    }
  }

  // Caves: where two ridged 3D noises are both near zero (tubes), between the surface and
  // caveDepthM below it. Tubes reach the surface, leaving cave mouths open, only where a 2D
  // noise allows (about a sixth of the land); elsewhere a roof of 4 m stays over them.
  if (options.features.caves) {
    const GradientNoise a(options.seed ^ 0xCA7EULL), b(options.seed ^ 0xB0A7ULL);
    const GradientNoise mouths(options.seed ^ 0x3007ULL);
    const double cell = std::min(spacing, 1.0);
    constexpr double kRoofM = 4.0;
    tbb::parallel_for(0, h, [&](int y) {
      for (int x = 0; x < w; ++x) {
        Column& c = columns[index(x, y)];
        const float g = groundOf(c);
        const bool mouth =
            mouths.sample(glm::dvec2(x * spacing, y * spacing) / options.caveScaleM).x > 0.3;
        const double upper = mouth ? double(g) + cell : double(g) - kRoofM;
        const double from = std::max(2.0, double(g) - options.caveDepthM);
        float carveFrom = -1.0f;
        for (double z = from; z < upper; z += cell) {
          const glm::dvec3 p = glm::dvec3(x * spacing, y * spacing, z * 1.6) / options.caveScaleM;
          const bool tube = std::abs(a.sample3(p)) < 0.07 && std::abs(b.sample3(p + 31.7)) < 0.07;
          if (tube && carveFrom < 0.0f) carveFrom = float(z);
          if (!tube && carveFrom >= 0.0f) {
            carve(c, carveFrom, float(z));
            carveFrom = -1.0f;
          }
        }
        if (carveFrom >= 0.0f) carve(c, carveFrom, mouth ? g + 1.0f : float(upper));
      }
    });
  }

  const std::size_t removed = removeFloatingLayers(w, h, columns);
  if (report) report->floatingLayersRemoved = removed;
  return StackTerrain::fromColumns(w, h, spacing, columns);
}

}  // namespace tellus
