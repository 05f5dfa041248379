#include "tellus/lod/ringo/ringo_layout.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>

#include "tellus/tiles/global_tiling.hpp"

namespace tellus {

int RingoLayout::levelAt(int dx, int dy) {
  return std::max(0, std::max(std::abs(dx), std::abs(dy)) - 1);
}

int RingoLayout::cellsAt(int level) const {
  return std::max(1, tileCells >> level);
}

std::uint64_t RingoLayout::trianglesAt(int level) const {
  const auto cells = std::uint64_t(cellsAt(level));
  return 2 * cells * cells;
}

std::uint64_t RingoLayout::totalTriangles() const {
  std::uint64_t total = 0;
  const int half = side() / 2;
  for (int dy = -half; dy <= half; ++dy) {
    for (int dx = -half; dx <= half; ++dx) total += trianglesAt(levelAt(dx, dy));
  }
  return total;
}

int minimumRingoDepth(const RingoLayout& layout) {
  int depth = 0;
  while (GlobalTiling::tilesX(depth) < layout.side()) ++depth;
  return depth;
}

int ringoDepthFor(double clearanceM, int deepestDepth, const RingoLayout& layout,
                  int currentDepth, double blocksToHorizon) {
  constexpr double kEarthRadiusM = 6371000.0;
  constexpr double kQuarterMeridianM = 10'001'966.0;  // ground length of 90 degrees
  const double clearance = std::max(clearanceM, 1.0);
  const double horizonM = std::sqrt(clearance * (2.0 * kEarthRadiusM + clearance));
  const double blockM = horizonM / std::max(blocksToHorizon, 1e-3);
  // A depth-d tile is 180 / 2^d degrees wide: 2 * kQuarterMeridianM / 2^d metres at the equator.
  const double depth = std::log2(2.0 * kQuarterMeridianM / blockM);
  const int lowest = minimumRingoDepth(layout);
  const int highest = std::max(lowest, deepestDepth);
  if (currentDepth >= lowest && currentDepth <= highest) {
    const double offset = std::clamp(depth, double(lowest), double(highest)) - currentDepth;
    if (offset >= -0.75 && offset < 0.5) return currentDepth;
  }
  return std::clamp(int(std::lround(depth)), lowest, highest);
}

double ringoPlannedClearance(double clearanceM, double lastClearanceM, int latencyFrames) {
  if (!(std::isfinite(lastClearanceM) && lastClearanceM > 0.0 && clearanceM < lastClearanceM)) {
    return clearanceM;
  }
  const double ratio = std::max(clearanceM / lastClearanceM, 0.25);
  return clearanceM * std::pow(ratio, latencyFrames);
}

double ringoPlannedClearanceInFlight(double eyeHeightM, double lastEyeHeightM, double groundM,
                                     double lastGroundM, int latencyFrames) {
  // The higher ground gives the smaller last clearance. std::max keeps groundM when lastGroundM
  // is NaN; a NaN last height stays NaN, which ringoPlannedClearance reads as no last frame.
  const double lastClearance = lastEyeHeightM - std::max(groundM, lastGroundM);
  return ringoPlannedClearance(eyeHeightM - groundM, lastClearance, latencyFrames);
}

RingoLatLon ringoPlannedPosition(RingoLatLon now, RingoLatLon last, int latencyFrames,
                                 double maxStepDeg) {
  const double stepLat = now.latDeg - last.latDeg;
  const double stepLon = std::remainder(now.lonDeg - last.lonDeg, 360.0);
  if (!(std::isfinite(stepLat) && std::isfinite(stepLon) && std::abs(stepLat) <= maxStepDeg &&
        std::abs(stepLon) <= maxStepDeg)) {
    return now;
  }
  RingoLatLon planned;
  planned.latDeg = std::clamp(now.latDeg + stepLat * latencyFrames, -90.0, 90.0);
  planned.lonDeg = std::remainder(now.lonDeg + stepLon * latencyFrames, 360.0);
  return planned;
}

}  // namespace tellus
