#include "tellus/formats/stacks/stack_aggregation.hpp"

#include <algorithm>
#include <array>
#include <optional>

namespace tellus {
namespace {

// The material of `column` at height h (air where no layer holds it).
StackMaterial materialAt(std::span<const StackLayer> column, double h) {
  for (const StackLayer& l : column) {
    if (h >= l.bottomM && h < l.topM) return l.material;
  }
  return kAir;
}

struct Segment {
  float bottomM = 0.0f, topM = 0.0f;
  int solid = 0, air = 0;             // columns holding some solid material, and air
  std::optional<bool> solidWins;      // the geometry's majority (none: a tie)
  std::vector<StackMaterial> tiedSolids;  // the solid materials sharing the highest count
};

// The class of segment i's majority when it has one (true: solid).
std::optional<bool> classOf(const std::vector<Segment>& segments, int i) {
  return segments[std::size_t(i)].solidWins;
}

// The surface of an aggregate shows what the columns' surfaces show: for each solid run of
// `layers` (touching layers), the columns' surface layers (the top layer of each column's solid
// run reaching nearest under the run's top) vote; when the winner is not the run's top
// material, it covers the run's top, as thick as those surface layers are on average (at most
// the run). Segment votes alone would bury a thin surface layer (grass) lying at different
// heights in the four columns under what lies below it.
void coverSurfaces(std::vector<StackLayer>& layers,
                   std::span<const std::span<const StackLayer>> columns) {
  for (std::size_t end = layers.size(); end > 0;) {
    std::size_t begin = end - 1;
    while (begin > 0 && layers[begin - 1].topM == layers[begin].bottomM) --begin;
    const float top = layers[end - 1].topM, runBottom = layers[begin].bottomM;
    std::array<int, 256> votes{};
    std::array<double, 256> thickness{};
    for (std::span<const StackLayer> column : columns) {
      // The highest layer of the column starting under the run's top, and its run's top layer.
      int found = -1;
      for (int l = 0; l < int(column.size()); ++l) {
        if (column[std::size_t(l)].bottomM < top && column[std::size_t(l)].topM > runBottom) found = l;
      }
      if (found < 0) continue;
      while (found + 1 < int(column.size()) &&
             column[std::size_t(found + 1)].bottomM == column[std::size_t(found)].topM) {
        ++found;
      }
      const StackLayer& surface = column[std::size_t(found)];
      ++votes[surface.material];
      thickness[surface.material] += double(surface.topM) - double(surface.bottomM);
    }
    const auto winner = StackMaterial(std::max_element(votes.begin(), votes.end()) - votes.begin());
    if (votes[winner] > 0 && winner != layers[end - 1].material &&
        votes[winner] > votes[layers[end - 1].material]) {
      const float depth = std::min(float(thickness[winner] / votes[winner]), top - runBottom);
      const float cut = top - depth;
      if (!(cut < top)) {  // a cover thinner than a float step at this height: none
        end = begin;
        continue;
      }
      // Trim the run's layers above the cut, then lay the surface material on top.
      while (end > begin && layers[end - 1].bottomM >= cut) {
        layers.erase(layers.begin() + std::ptrdiff_t(end - 1));
        --end;
      }
      if (end > begin) layers[end - 1].topM = cut;
      layers.insert(layers.begin() + std::ptrdiff_t(end), StackLayer{cut, top, winner});
      if (end > begin && layers[end - 1].material == winner) {  // merge with a same-material layer
        layers[end - 1].topM = top;
        layers.erase(layers.begin() + std::ptrdiff_t(end));
      }
    }
    end = begin;
  }
}

}  // namespace

std::vector<StackLayer> aggregateColumns(std::span<const std::span<const StackLayer>> columns) {
  if (columns.size() > 4) columns = columns.first(4);  // the contract: one to four columns
  std::vector<float> bounds;
  for (std::span<const StackLayer> column : columns) {
    for (const StackLayer& l : column) {
      bounds.push_back(l.bottomM);
      bounds.push_back(l.topM);
    }
  }
  std::sort(bounds.begin(), bounds.end());
  bounds.erase(std::unique(bounds.begin(), bounds.end()), bounds.end());
  std::vector<Segment> segments;
  for (std::size_t i = 0; i + 1 < bounds.size(); ++i) {
    Segment s;
    s.bottomM = bounds[i];
    s.topM = bounds[i + 1];
    const double middle = 0.5 * (double(s.bottomM) + double(s.topM));
    // The (at most four) columns' materials here, and how many columns hold each solid one.
    std::array<std::pair<StackMaterial, int>, 4> solids{};
    int distinct = 0;
    for (std::span<const StackLayer> column : columns) {
      const StackMaterial m = materialAt(column, middle);
      if (m == kAir) {
        ++s.air;
        continue;
      }
      int k = 0;
      while (k < distinct && solids[std::size_t(k)].first != m) ++k;
      if (k == distinct) solids[std::size_t(distinct++)] = {m, 0};
      ++solids[std::size_t(k)].second;
    }
    s.solid = int(columns.size()) - s.air;
    if (s.solid != s.air) s.solidWins = s.solid > s.air;
    int most = 0;
    for (int k = 0; k < distinct; ++k) most = std::max(most, solids[std::size_t(k)].second);
    for (int k = 0; k < distinct; ++k) {
      if (solids[std::size_t(k)].second == most) s.tiedSolids.push_back(solids[std::size_t(k)].first);
    }
    std::sort(s.tiedSolids.begin(), s.tiedSolids.end());  // by material id, as before
    segments.push_back(std::move(s));
  }
  // Thickness of each material over the columns: the last resort of the ties.
  std::array<double, 256> thickness{};
  for (std::span<const StackLayer> column : columns) {
    for (const StackLayer& l : column) thickness[l.material] += double(l.topM) - double(l.bottomM);
  }
  const int n = int(segments.size());
  // The materials of a solid piece of segment i (lower half, upper half): its most common
  // solid material. On a tie among solid materials, at the surface (air above the piece) the
  // tied material found nearest above, so a surface keeps its own material (grass over soil
  // at slightly different heights would otherwise lose the grass); inside the solid the
  // seed's rules on the nearest segments with a dominant solid material: one side's, or both
  // halves when they differ; then the thickest.
  const auto dominantSolid = [&](int j, const std::vector<StackMaterial>& tied) -> std::optional<StackMaterial> {
    const std::vector<StackMaterial>& d = segments[std::size_t(j)].tiedSolids;
    if (d.size() == 1 && std::find(tied.begin(), tied.end(), d.front()) != tied.end()) return d.front();
    return std::nullopt;
  };
  const auto solidMaterials = [&](int i, bool surface) -> std::pair<StackMaterial, StackMaterial> {
    const std::vector<StackMaterial>& tied = segments[std::size_t(i)].tiedSolids;
    if (tied.size() == 1) return {tied.front(), tied.front()};
    if (surface) {
      for (int j = i + 1; j < n; ++j) {
        for (StackMaterial m : segments[std::size_t(j)].tiedSolids) {
          if (std::find(tied.begin(), tied.end(), m) != tied.end()) return {m, m};
        }
      }
    }
    for (int d = 1; i - d >= 0 || i + d < n; ++d) {
      const std::optional<StackMaterial> below = i - d >= 0 ? dominantSolid(i - d, tied) : std::nullopt;
      const std::optional<StackMaterial> above = i + d < n ? dominantSolid(i + d, tied) : std::nullopt;
      if (below.has_value() || above.has_value()) {
        const StackMaterial low = below.value_or(above.value_or(kAir));
        const StackMaterial high = above.value_or(low);
        return {low, high};
      }
    }
    StackMaterial best = tied.front();
    for (StackMaterial m : tied) {
      if (thickness[m] > thickness[best]) best = m;
    }
    return {best, best};
  };

  std::vector<StackLayer> pieces;  // (bottom, top, material), air included, bottom up
  for (int i = 0; i < n; ++i) {
    const Segment& s = segments[std::size_t(i)];
    const float middle = 0.5f * (s.bottomM + s.topM);
    // A piece of the segment; `surface`: air lies directly above it.
    const auto piece = [&](float bottom, float top, bool solid, bool surface) {
      if (!solid) {
        pieces.push_back({bottom, top, kAir});
        return;
      }
      const auto [lower, upper] = solidMaterials(i, surface);
      if (lower == upper || top <= middle || bottom >= middle) {
        pieces.push_back({bottom, top, top <= middle ? lower : upper});
        return;
      }
      pieces.push_back({bottom, middle, lower});
      pieces.push_back({middle, top, upper});
    };
    const auto airAbove = [&] { return i + 1 >= n || classOf(segments, i + 1) == std::optional<bool>(false); };
    if (s.solidWins) {
      piece(s.bottomM, s.topM, *s.solidWins, airAbove());
      continue;
    }
    // A tie between solid and air: the nearest decided neighbours choose (rules 2a-2c).
    bool decided = false;
    for (int d = 1; !decided && (i - d >= 0 || i + d <= n); ++d) {
      const std::optional<bool> below = i - d >= 0 ? classOf(segments, i - d) : std::nullopt;
      // Above the highest segment is the sky.
      const std::optional<bool> above =
          i + d < n ? classOf(segments, i + d) : (i + d == n ? std::optional<bool>(false) : std::nullopt);
      if (below && above && *below != *above) {
        piece(s.bottomM, middle, *below, !*above);
        piece(middle, s.topM, *above, airAbove());
        decided = true;
      } else if (below || above) {
        piece(s.bottomM, s.topM, below ? *below : *above, airAbove());
        decided = true;
      }
    }
    if (!decided) {
      double solidThickness = 0.0;
      for (int m = 1; m < 256; ++m) solidThickness += thickness[std::size_t(m)];
      piece(s.bottomM, s.topM, solidThickness >= thickness[kAir], airAbove());
    }
  }
  std::vector<StackLayer> layers;
  for (const StackLayer& p : pieces) {
    if (p.material == kAir || !(p.topM > p.bottomM)) continue;
    if (!layers.empty() && layers.back().material == p.material && layers.back().topM == p.bottomM) {
      layers.back().topM = p.topM;
    } else {
      layers.push_back(p);
    }
  }
  coverSurfaces(layers, columns);
  return layers;
}

Result<StackTerrain> tryAggregateStackTerrain(const StackTerrain& fine) {
  const int width = (fine.width() + 1) / 2, height = (fine.height() + 1) / 2;
  std::vector<std::vector<StackLayer>> columns;
  columns.reserve(std::size_t(width) * std::size_t(height));
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      std::vector<std::span<const StackLayer>> four;
      for (int dy = 0; dy < 2; ++dy) {
        for (int dx = 0; dx < 2; ++dx) {
          if (2 * x + dx < fine.width() && 2 * y + dy < fine.height()) {
            four.push_back(fine.column(2 * x + dx, 2 * y + dy));
          }
        }
      }
      columns.push_back(aggregateColumns(four));
    }
  }
  // Aggregates of valid columns are valid: sorted, solid, positive, not overlapping (a
  // fuzzer's layers a float step thick once broke that: checked, not assumed).
  return StackTerrain::fromColumns(width, height, 2.0 * fine.spacingM(), columns);
}

StackTerrain aggregateStackTerrain(const StackTerrain& fine) {
  return tryAggregateStackTerrain(fine).value();
}

std::vector<StackTerrain> buildStackPyramid(StackTerrain finest) {
  std::vector<StackTerrain> levels;
  levels.push_back(std::move(finest));
  while (levels.back().width() > 1 || levels.back().height() > 1) {
    levels.push_back(aggregateStackTerrain(levels.back()));
  }
  return levels;
}

}  // namespace tellus
