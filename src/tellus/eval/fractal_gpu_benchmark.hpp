#pragma once
// Speed of the fractal codec's GPU decoder on many tiles: payloads are parsed on the CPU, their
// codes uploaded, iterated to their full count on the GPU and published as heights (with the
// residual layer when present). Used by `tellus bench codecs`. Needs a current GL 4.5 context.
#include <cstddef>
#include <span>
#include <vector>

#include "tellus/core/result.hpp"
#include "tellus/tiles/tile_codec.hpp"

namespace tellus {

struct FractalGpuDecodeMeasurement {
  double totalSeconds = 0.0;  // parse + upload + iterate + publish, all tiles (median)
  double gpuSeconds = 0.0;    // iterate + publish only, codes already uploaded (median)
  double meanIterations = 0.0;
};

Result<FractalGpuDecodeMeasurement> measureFractalGpuDecode(
    std::span<const std::vector<std::byte>> payloads, TileShape shape, int repeats);

}  // namespace tellus
