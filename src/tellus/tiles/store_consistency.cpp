#include "tellus/tiles/store_consistency.hpp"

#include <cstdlib>

#include <fmt/format.h>

namespace tellus {
namespace {

// Line indices in Lines::line.
constexpr int kRow0 = 0, kRowN = 2, kCol0 = 3, kColN = 5;  // rows 0, n/2, n, then columns

}  // namespace

StoreConsistency::StoreConsistency(const TileStore& store)
    : store_(store), n_(store.layout().tileSize()), lines_(store.records().size()) {
  const StoreMetadata& m = store.metadata();
  if (store.codec().lossless()) {
    tolerance_ = 0;
  } else if (!m.maxErrorMeasured) {  // the bound is guaranteed (fractal: with its residual)
    tolerance_ = 2 * std::int64_t(m.maxErrorSteps);
  }
}

void StoreConsistency::addTile(const TileRecord& record, std::span<const std::int32_t> samples) {
  const std::size_t index = std::size_t(&record - store_.records().data());
  if (index >= lines_.size() || samples.size() != std::size_t(n_ + 1) * std::size_t(n_ + 1)) return;
  Lines& lines = lines_[index];
  const std::size_t side = std::size_t(n_ + 1);
  const int at[3] = {0, n_ / 2, n_};
  for (int k = 0; k < 3; ++k) {
    std::vector<std::int32_t>& row = lines.line[kRow0 + k];
    std::vector<std::int32_t>& column = lines.line[kCol0 + k];
    row.resize(side);
    column.resize(side);
    for (std::size_t i = 0; i < side; ++i) {
      row[i] = samples[std::size_t(at[k]) * side + i];
      column[i] = samples[i * side + std::size_t(at[k])];
    }
  }
}

const StoreConsistency::Lines* StoreConsistency::linesOf(TileKey key) const {
  const TileRecord* record = store_.find(key);
  if (!record) return nullptr;
  const Lines& lines = lines_[std::size_t(record - store_.records().data())];
  return lines.line[0].empty() ? nullptr : &lines;
}

std::string StoreConsistency::where(TileKey key) const {
  return fmt::format("'{}': {}", store_.path().string(), TileStore::describe(key));
}

void StoreConsistency::compareEdges(TileKey key, std::vector<std::string>& problems) const {
  const Lines* mine = linesOf(key);
  if (!mine) return;
  const PyramidLayout& layout = store_.layout();
  const std::int64_t stride = PyramidLayout::stride(key.level);
  const double q = store_.metadata().quantumM;
  const std::int64_t x0 = std::int64_t(key.x) * n_, y0 = std::int64_t(key.y) * n_;
  // Level positions whose level-0 position is inside the data (padding repeats the last sample
  // and is not compared); `last` is the data's last level-0 position on that axis.
  const auto onData = [&](std::int64_t position, int last) { return position * stride <= last; };
  // My line and the neighbour's first along one shared edge, whose samples start at level
  // position `first` on an axis ending at `last`; false when they differ.
  const auto sameEdge = [&](const std::vector<std::int32_t>& ours, const std::vector<std::int32_t>& theirs,
                            std::int64_t first, int last, const char* neighbour, const char* along) {
    for (int k = 0; k <= n_ && onData(first + k, last); ++k) {
      const std::int32_t a = ours[std::size_t(k)], b = theirs[std::size_t(k)];
      if (std::abs(std::int64_t(a) - b) > *tolerance_) {
        problems.push_back(fmt::format("{} and its {} neighbour differ on their shared edge ({} {}: "
                                       "{} m vs {} m): a tile out of place?",
                                       where(key), neighbour, along, k, a * q, b * q));
        return false;
      }
    }
    return true;
  };
  const Lines* east = linesOf({key.level, key.x + 1, key.y});
  if (east && onData(x0 + n_, layout.dataWidth() - 1) &&
      !sameEdge(mine->line[kColN], east->line[kCol0], y0, layout.dataHeight() - 1, "eastern", "row")) {
    return;
  }
  const Lines* south = linesOf({key.level, key.x, key.y + 1});
  if (south && onData(y0 + n_, layout.dataHeight() - 1)) {
    sameEdge(mine->line[kRowN], south->line[kRow0], x0, layout.dataWidth() - 1, "southern", "column");
  }
}

void StoreConsistency::compareWithParent(TileKey key, std::vector<std::string>& problems) const {
  const PyramidLayout& layout = store_.layout();
  if (key.level + 1 >= layout.levelCount()) return;
  const Lines* child = linesOf(key);
  const Lines* parent = linesOf({key.level + 1, key.x / 2, key.y / 2});
  if (!child || !parent) return;
  const std::int64_t stride = PyramidLayout::stride(key.level);
  const std::int64_t x0 = std::int64_t(key.x) * n_, y0 = std::int64_t(key.y) * n_;
  const int dx = key.x % 2, dy = key.y % 2;
  const double q = store_.metadata().quantumM;
  const std::int64_t tol = *tolerance_;
  // A parent line index for a parent row or column 0, n/2 or n.
  const auto parentLine = [&](int first, int at) { return first + (at == 0 ? 0 : at == n_ / 2 ? 1 : 2); };
  const auto onData = [&](std::int64_t i, std::int64_t j) {
    return (x0 + i) * stride <= layout.dataWidth() - 1 && (y0 + j) * stride <= layout.dataHeight() - 1;
  };
  const auto report = [&](int i, int j, std::int32_t mineValue, std::int32_t theirs) {
    problems.push_back(fmt::format("{} sample ({}, {}) is {} m, its parent {} holds {} m there: a "
                                   "tile out of place?",
                                   where(key), i, j, mineValue * q,
                                   TileStore::describe({key.level + 1, key.x / 2, key.y / 2}), theirs * q));
  };
  // The child's first and last rows, at even columns, against the parent's rows.
  for (const int r : {0, n_}) {
    const std::vector<std::int32_t>& row = child->line[r == 0 ? kRow0 : kRowN];
    const std::vector<std::int32_t>& theirs = parent->line[parentLine(kRow0, (dy * n_ + r) / 2)];
    for (int i = 0; i <= n_; i += 2) {
      if (!onData(i, r)) continue;
      const std::int32_t a = row[std::size_t(i)], b = theirs[std::size_t((dx * n_ + i) / 2)];
      if (std::abs(std::int64_t(a) - b) > tol) return report(i, r, a, b);
    }
  }
  // Its first and last columns, at even rows, against the parent's columns.
  for (const int c : {0, n_}) {
    const std::vector<std::int32_t>& column = child->line[c == 0 ? kCol0 : kColN];
    const std::vector<std::int32_t>& theirs = parent->line[parentLine(kCol0, (dx * n_ + c) / 2)];
    for (int j = 0; j <= n_; j += 2) {
      if (!onData(c, j)) continue;
      const std::int32_t a = column[std::size_t(j)], b = theirs[std::size_t((dy * n_ + j) / 2)];
      if (std::abs(std::int64_t(a) - b) > tol) return report(c, j, a, b);
    }
  }
}

std::vector<std::string> StoreConsistency::check(std::size_t limit) const {
  std::vector<std::string> problems;
  if (!tolerance_) return problems;
  for (const TileRecord& record : store_.records()) {
    if (problems.size() >= limit) break;
    compareEdges(record.key, problems);
    compareWithParent(record.key, problems);
  }
  if (problems.size() > limit) problems.resize(limit);
  return problems;
}

}  // namespace tellus
