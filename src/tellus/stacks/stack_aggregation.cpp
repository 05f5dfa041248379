#include "tellus/stacks/stack_aggregation.hpp"

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
  float bottomM, topM;
  std::array<int, 256> counts{};
  std::optional<StackMaterial> dominant;
  std::vector<StackMaterial> tied;  // the materials sharing the highest count (no dominant)
};

}  // namespace

std::vector<StackLayer> aggregateColumns(std::span<const std::span<const StackLayer>> columns) {
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
    Segment s{bounds[i], bounds[i + 1], {}, {}, {}};
    const double middle = 0.5 * (double(s.bottomM) + double(s.topM));
    for (std::span<const StackLayer> column : columns) ++s.counts[materialAt(column, middle)];
    const int most = *std::max_element(s.counts.begin(), s.counts.end());
    for (int m = 0; m < 256; ++m) {
      if (s.counts[std::size_t(m)] == most) s.tied.push_back(StackMaterial(m));
    }
    if (s.tied.size() == 1) s.dominant = s.tied.front();
    segments.push_back(std::move(s));
  }
  // Thickness of each material over the columns: the last resort of rule 2c.
  std::array<double, 256> thickness{};
  for (std::span<const StackLayer> column : columns) {
    for (const StackLayer& l : column) thickness[l.material] += double(l.topM) - double(l.bottomM);
  }

  std::vector<StackLayer> pieces;  // (bottom, top, material), air included, bottom up
  const int n = int(segments.size());
  for (int i = 0; i < n; ++i) {
    const Segment& s = segments[std::size_t(i)];
    if (s.dominant) {
      pieces.push_back({s.bottomM, s.topM, *s.dominant});
      continue;
    }
    const auto isTied = [&](std::optional<StackMaterial> m) {
      return m && std::find(s.tied.begin(), s.tied.end(), *m) != s.tied.end();
    };
    bool decided = false;
    for (int d = 1; !decided && (i - d >= 0 || i + d <= n); ++d) {
      const std::optional<StackMaterial> below =
          i - d >= 0 ? segments[std::size_t(i - d)].dominant : std::nullopt;
      // Above the highest segment is the sky.
      const std::optional<StackMaterial> above =
          i + d < n ? segments[std::size_t(i + d)].dominant
                    : (i + d == n ? std::optional<StackMaterial>(kAir) : std::nullopt);
      const bool fromBelow = isTied(below), fromAbove = isTied(above);
      if (fromBelow && fromAbove && *below != *above) {
        const float middle = 0.5f * (s.bottomM + s.topM);
        pieces.push_back({s.bottomM, middle, *below});
        pieces.push_back({middle, s.topM, *above});
        decided = true;
      } else if (fromBelow || fromAbove) {
        pieces.push_back({s.bottomM, s.topM, fromBelow ? *below : *above});
        decided = true;
      }
    }
    if (!decided) {
      StackMaterial best = s.tied.front();
      for (StackMaterial m : s.tied) {
        const bool thicker = thickness[m] > thickness[best];
        const bool solidOnEqual = thickness[m] == thickness[best] && best == kAir && m != kAir;
        if (thicker || solidOnEqual) best = m;
      }
      pieces.push_back({s.bottomM, s.topM, best});
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
  return layers;
}

StackTerrain aggregateStackTerrain(const StackTerrain& fine) {
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
  // Aggregates of valid columns are valid: sorted, solid, positive, not overlapping.
  return StackTerrain::fromColumns(width, height, 2.0 * fine.spacingM(), columns).value();
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
