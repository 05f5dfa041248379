#include "tellus/eval/fractal_benchmark.hpp"

#include <algorithm>
#include <cmath>

#include <tbb/parallel_for.h>

#include "tellus/tiles/fractal_format.hpp"

namespace tellus {

Result<std::vector<ConvergencePoint>> measureFractalConvergence(
    const std::vector<std::vector<std::byte>>& payloads, const QuantisedTiles& tiles,
    const HeightGrid& grid, double quantumM, int maxIterations) {
  std::vector<fractal::FractalCode> codes;
  for (const std::vector<std::byte>& payload : payloads) {
    Result<fractal::FractalCode> code = fractal::read(payload, tiles.shape);
    if (!code) return code.error();
    codes.push_back(std::move(code.value()));
  }
  const auto [lo, hi] = std::minmax_element(grid.heights.begin(), grid.heights.end());
  const double relief = std::max(double(*hi) - double(*lo), quantumM);
  std::vector<ConvergencePoint> points;
  std::vector<std::vector<std::int32_t>> decoded(
      tiles.tiles.size(), std::vector<std::int32_t>(tiles.shape.sampleCount()));
  for (int k = 1; k <= maxIterations; ++k) {
    tbb::parallel_for(std::size_t(0), codes.size(), [&](std::size_t t) {
      fractal::workingToSamples(codes[t], fractal::decodeWorking(codes[t], k), false, decoded[t]);
    });
    ConvergencePoint p;
    p.iterations = k;
    compareHeights(assembleTiles(decoded, tiles, grid, quantumM), grid.heights, p.maxAbsErrorM,
                   p.rmseM);
    p.psnrDb = p.rmseM > 0.0 ? 20.0 * std::log10(relief / p.rmseM) : INFINITY;
    points.push_back(p);
  }
  return points;
}

}  // namespace tellus
