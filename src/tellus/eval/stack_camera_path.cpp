#include "tellus/eval/stack_camera_path.hpp"

#include <algorithm>
#include <cmath>
#include <deque>

namespace tellus {
namespace {

struct Gap {
  float bottomM = 0.0f, topM = -1.0f;  // none when topM < bottomM
  bool exists() const { return topM >= bottomM; }
  float height() const { return topM - bottomM; }
};

// The tallest gap between two solid layers of a column.
Gap tallestGap(std::span<const StackLayer> column) {
  Gap best;
  for (std::size_t i = 0; i + 1 < column.size(); ++i) {
    const Gap gap{column[i].topM, column[i + 1].bottomM};
    if (gap.height() > 0.0f && (!best.exists() || gap.height() > best.height())) best = gap;
  }
  return best;
}

}  // namespace

Result<CameraPath> makeCavePath(const StackTerrain& stacks, double minGapM, StackPassage* report) {
  const int w = stacks.width(), h = stacks.height();
  const auto index = [w](int x, int row) { return std::size_t(x) + std::size_t(w) * std::size_t(row); };
  std::vector<Gap> gaps(std::size_t(w) * std::size_t(h));
  for (int row = 0; row < h; ++row) {
    for (int x = 0; x < w; ++x) {
      const Gap gap = tallestGap(stacks.column(x, row));
      if (gap.exists() && gap.height() >= float(minGapM)) gaps[index(x, row)] = gap;
    }
  }
  // Columns a walk may use (all passage columns at first, then the passage's core).
  std::vector<std::uint8_t> allowed(gaps.size(), 1);
  const auto joined = [&](std::size_t a, std::size_t b) {
    const Gap& ga = gaps[a];
    const Gap& gb = gaps[b];
    return allowed[b] && gb.exists() &&
           std::min(ga.topM, gb.topM) - std::max(ga.bottomM, gb.bottomM) >= 0.5f * float(minGapM);
  };
  const int dx[4] = {1, -1, 0, 0}, dy[4] = {0, 0, 1, -1};
  // Breadth-first search from `start` over joined columns: distances (-1 unreached) and parents.
  const auto search = [&](std::size_t start, std::vector<int>& distance, std::vector<std::size_t>& parent) {
    distance.assign(gaps.size(), -1);
    parent.assign(gaps.size(), start);
    std::deque<std::size_t> queue{start};
    distance[start] = 0;
    std::size_t farthest = start;
    while (!queue.empty()) {
      const std::size_t c = queue.front();
      queue.pop_front();
      if (distance[c] > distance[farthest]) farthest = c;
      const int x = int(c % std::size_t(w)), row = int(c / std::size_t(w));
      for (int k = 0; k < 4; ++k) {
        const int nx = x + dx[k], ny = row + dy[k];
        if (nx < 0 || ny < 0 || nx >= w || ny >= h) continue;
        const std::size_t n = index(nx, ny);
        if (distance[n] >= 0 || !joined(c, n)) continue;
        distance[n] = distance[c] + 1;
        parent[n] = c;
        queue.push_back(n);
      }
    }
    return farthest;
  };
  // The largest passage.
  std::vector<int> component(gaps.size(), -1);
  std::size_t bestStart = 0, bestSize = 0;
  std::vector<int> distance;
  std::vector<std::size_t> parent;
  for (std::size_t c = 0; c < gaps.size(); ++c) {
    if (!gaps[c].exists() || component[c] >= 0) continue;
    search(c, distance, parent);
    std::size_t size = 0;
    for (std::size_t k = 0; k < gaps.size(); ++k) {
      if (distance[k] >= 0) {
        component[k] = int(c);
        ++size;
      }
    }
    if (size > bestSize) {
      bestSize = size;
      bestStart = c;
    }
  }
  if (bestSize < 8) {
    return makeError("no cave or arch opening of at least {:.1f} m over 8 stacks to walk through "
                     "(the largest spans {} stacks)", minGapM, bestSize);
  }
  // The longest walk of a piece of allowed columns: from `a`, the farthest column of the piece
  // from any of its columns (search()'s result), to the farthest column from `a`.
  const auto longestWalkFrom = [&](std::size_t a) {
    const std::size_t b = search(a, distance, parent);
    std::vector<std::size_t> walk{b};
    while (walk.back() != a) walk.push_back(parent[walk.back()]);
    return walk;
  };
  const std::vector<std::size_t> fullWalk = longestWalkFrom(search(bestStart, distance, parent));
  // Clearance: how many columns (8-neighbour steps) a passage column lies from the nearest
  // column outside the passage (1: it touches rock). A camera on a wall column is half a
  // stack from the rock, and its near plane (0.5 m, wider than that across a 70 degree view)
  // can cut into it, so the walk keeps to the passage's core: the columns of the largest
  // clearance (up to 3) whose longest walk is still at least half the passage's.
  const int passage = component[bestStart];
  const auto inPassage = [&](int x, int row) {
    return x >= 0 && row >= 0 && x < w && row < h && component[index(x, row)] == passage;
  };
  std::vector<int> clearance(gaps.size(), 0);
  std::deque<std::size_t> queue;
  for (std::size_t c = 0; c < gaps.size(); ++c) {
    if (component[c] != passage) continue;
    const int x = int(c % std::size_t(w)), row = int(c / std::size_t(w));
    bool wall = false;
    for (int ny = row - 1; ny <= row + 1; ++ny)
      for (int nx = x - 1; nx <= x + 1; ++nx) wall = wall || !inPassage(nx, ny);
    if (wall) {
      clearance[c] = 1;
      queue.push_back(c);
    }
  }
  while (!queue.empty()) {
    const std::size_t c = queue.front();
    queue.pop_front();
    const int x = int(c % std::size_t(w)), row = int(c / std::size_t(w));
    for (int ny = row - 1; ny <= row + 1; ++ny) {
      for (int nx = x - 1; nx <= x + 1; ++nx) {
        if (!inPassage(nx, ny) || clearance[index(nx, ny)] > 0) continue;
        clearance[index(nx, ny)] = clearance[c] + 1;
        queue.push_back(index(nx, ny));
      }
    }
  }
  std::vector<std::size_t> walk = fullWalk;
  for (int core = 3; core >= 2; --core) {
    for (std::size_t c = 0; c < gaps.size(); ++c) allowed[c] = clearance[c] >= core ? 1 : 0;
    // The core's largest piece: its longest walk.
    std::vector<std::size_t> best;
    std::vector<std::uint8_t> seen(gaps.size(), 0);
    for (std::size_t c = 0; c < gaps.size(); ++c) {
      if (!allowed[c] || seen[c]) continue;
      const std::size_t a = search(c, distance, parent);
      for (std::size_t k = 0; k < gaps.size(); ++k) seen[k] = seen[k] || distance[k] >= 0;
      std::vector<std::size_t> candidate = longestWalkFrom(a);
      if (candidate.size() > best.size()) best = std::move(candidate);
    }
    if (best.size() >= 8 && 2 * best.size() >= fullWalk.size()) {
      walk = std::move(best);
      break;
    }
  }
  const double s = stacks.spacingM();
  const auto position = [&](std::size_t c) {
    const int x = int(c % std::size_t(w)), row = int(c / std::size_t(w));
    const Gap& gap = gaps[c];
    return glm::dvec3(x * s, (h - 1 - row) * s, gap.bottomM + 0.4 * gap.height());
  };
  // A keyframe every few columns, so the interpolated path follows the walk's turns.
  const std::size_t step = std::clamp<std::size_t>(walk.size() / 24, 1, 3);
  std::vector<CameraKeyframe> keyframes;
  double timeS = 0.0, lengthM = 0.0, gapSum = 0.0;
  for (std::size_t i = 0; i < walk.size(); i += step) {
    const std::size_t ahead = std::min(walk.size() - 1, i + 2 * step);
    const glm::dvec3 p = position(walk[i]);
    glm::dvec3 towards = position(walk[ahead]) - p;
    if (ahead == i) towards = p - position(walk[i >= step ? i - step : 0]);
    CameraKeyframe key;
    if (!keyframes.empty()) {
      const double d = glm::length(p - keyframes.back().camera.position);
      lengthM += d;
      timeS += std::max(d, 1e-3) / 5.0;  // 5 m/s
    }
    key.timeS = timeS;
    key.camera.position = p;
    key.camera.yawDeg = std::atan2(towards.x, towards.y) * 180.0 / M_PI;
    key.camera.pitchDeg = 0.0;
    key.camera.fovYDeg = 70.0;
    keyframes.push_back(key);
    gapSum += gaps[walk[i]].height();
  }
  if (keyframes.size() < 2) return makeError("the passage is too short to walk through");
  if (report) *report = {bestSize, lengthM, gapSum / double(keyframes.size())};
  return CameraPath::fromKeyframes(std::move(keyframes));
}

}  // namespace tellus
