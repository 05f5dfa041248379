#pragma once
// Convergence of the fractal decoder on a whole grid: the fractal payloads of the grid's tiles
// (cut as the pyramid builder cuts them, encoded by measureCodec) are decoded with 1, 2, ...
// iterations from a flat image and compared with the grid. Used by `tellus bench codecs`.
#include <vector>

#include "tellus/core/result.hpp"
#include "tellus/eval/codec_benchmark.hpp"

namespace tellus {

struct ConvergencePoint {
  int iterations = 0;
  double rmseM = 0.0;
  double maxAbsErrorM = 0.0;
  double psnrDb = 0.0;  // 20 log10(grid relief / RMSE)
};

Result<std::vector<ConvergencePoint>> measureFractalConvergence(
    const std::vector<std::vector<std::byte>>& payloads, const QuantisedTiles& tiles,
    const HeightGrid& grid, double quantumM, int maxIterations);

}  // namespace tellus
