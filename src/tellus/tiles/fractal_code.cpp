#include "tellus/tiles/fractal_code.hpp"

#include <algorithm>
#include <cstdlib>

#include "tellus/tiles/sample_coding.hpp"

namespace tellus::fractal {

std::vector<std::uint32_t> flatImage(const FractalCode& code) {
  return std::vector<std::uint32_t>(std::size_t(code.paddedSide) * std::size_t(code.paddedSide),
                                    0u);
}

void iterate(const FractalCode& code, std::span<const std::uint32_t> in,
             std::span<std::uint32_t> out) {
  const std::size_t side = std::size_t(code.paddedSide);
  std::uint32_t shrunk[16 * 16];
  for (const RangeBlock& range : code.ranges) {
    const int r = 1 << range.sizeLog2;
    std::uint32_t* target = out.data() + range.y * side + range.x;
    if (range.scaleIndex == 0) {
      for (int y = 0; y < r; ++y) std::fill_n(target + std::size_t(y) * side, r, range.mean);
      continue;
    }
    // Shrink the domain by 2x2 averaging (floor), then take its mean (floor).
    std::uint32_t sum = 0;
    for (int v = 0; v < r; ++v) {
      const std::uint32_t* row0 =
          in.data() + (range.domainY + 2 * std::size_t(v)) * side + range.domainX;
      const std::uint32_t* row1 = row0 + side;
      for (int u = 0; u < r; ++u) {
        const std::uint32_t value =
            (row0[2 * u] + row0[2 * u + 1] + row1[2 * u] + row1[2 * u + 1]) >> 2;
        shrunk[v * r + u] = value;
        sum += value;
      }
    }
    const std::int32_t domainMean = std::int32_t(sum >> (2 * range.sizeLog2));
    const std::int32_t mean = std::int32_t(range.mean);
    for (int y = 0; y < r; ++y) {
      std::uint32_t* line = target + std::size_t(y) * side;
      for (int x = 0; x < r; ++x) {
        int u = 0, v = 0;
        isometryPosition(range.isometry, x, y, r, u, v);
        const std::int32_t deviation = std::int32_t(shrunk[v * r + u]) - domainMean;
        const std::int32_t value =
            mean + ((range.scaleIndex * deviation + (1 << (kScaleBits - 1))) >> kScaleBits);
        line[x] = std::uint32_t(std::clamp<std::int32_t>(value, 0, std::int32_t(kMaxWorking)));
      }
    }
  }
}

std::vector<std::uint32_t> decodeWorking(const FractalCode& code, int iterations) {
  std::vector<std::uint32_t> a = flatImage(code), b = flatImage(code);
  for (int i = 0; i < iterations; ++i) {
    iterate(code, a, b);
    a.swap(b);
  }
  return a;
}

void workingToSamples(const FractalCode& code, std::span<const std::uint32_t> working,
                      bool withResidual, std::span<std::int32_t> samples) {
  const int w = code.shape.width, h = code.shape.height;
  const bool residual = withResidual && code.hasResidual;
  const std::uint64_t bin = 2 * std::uint64_t(code.residualError) + 1;
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      const std::size_t i = std::size_t(y) * std::size_t(w) + std::size_t(x);
      const std::uint32_t value = working[std::size_t(y) * std::size_t(code.paddedSide) + x];
      // Arithmetic modulo 2^32, as the other codecs, so hostile codes cannot overflow.
      std::uint32_t sample = std::uint32_t(code.base) + ((value + kOne / 2) >> kFractionBits);
      if (residual) sample += std::uint32_t(std::uint64_t(std::int64_t(code.residual[i])) * bin);
      samples[i] = std::int32_t(sample);
    }
  }
  if (!code.border.empty()) {
    forEachBorderSample(code.shape, [&](int k, int x, int y) {
      samples[std::size_t(y) * std::size_t(w) + std::size_t(x)] =
          std::int32_t(std::uint32_t(code.base) + std::uint32_t(code.border[std::size_t(k)]));
    });
  }
}

Status validate(const FractalCode& code) {
  const int side = code.paddedSide;
  if (side < 2 || side > coding::kMaxTileSide + 32 || side < code.shape.width ||
      side < code.shape.height) {
    return makeError("fractal tile has a padded side of {} for a {}x{} tile", side,
                     code.shape.width, code.shape.height);
  }
  if (code.iterations < 0 || code.iterations > kMaxIterations) {
    return makeError("fractal tile asks for {} iterations", code.iterations);
  }
  std::vector<bool> covered(std::size_t(side) * std::size_t(side), false);
  for (const RangeBlock& range : code.ranges) {
    const int r = 1 << range.sizeLog2;
    if (range.sizeLog2 < kMinRangeLog2 || range.sizeLog2 > kMaxRangeLog2 || range.x + r > side ||
        range.y + r > side) {
      return makeError("fractal range block at ({}, {}) of size {} leaves the tile", range.x,
                       range.y, r);
    }
    if (range.isometry > 7 || std::abs(range.scaleIndex) > kMaxScaleIndex ||
        range.mean > kMaxWorking) {
      return makeError("fractal range block at ({}, {}) has invalid parameters", range.x, range.y);
    }
    if (range.scaleIndex != 0 && (range.domainX + 2 * r > side || range.domainY + 2 * r > side)) {
      return makeError("fractal domain block at ({}, {}) leaves the tile", range.domainX,
                       range.domainY);
    }
    for (int y = range.y; y < range.y + r; ++y) {
      for (int x = range.x; x < range.x + r; ++x) {
        const std::size_t i = std::size_t(y) * std::size_t(side) + std::size_t(x);
        if (covered[i]) return makeError("fractal range blocks overlap at ({}, {})", x, y);
        covered[i] = true;
      }
    }
  }
  if (std::find(covered.begin(), covered.end(), false) != covered.end()) {
    return makeError("fractal range blocks do not cover the tile");
  }
  if (!code.border.empty()) {
    if (code.border.size() != std::size_t(borderLength(code.shape))) {
      return makeError("fractal border holds {} samples, expected {}", code.border.size(),
                       borderLength(code.shape));
    }
    for (const std::int32_t b : code.border) {
      if (b < 0 || b > kMaxReliefSteps) {
        return makeError("fractal border sample {} is outside the tile's relief", b);
      }
    }
  }
  if (code.hasResidual && code.residual.size() != code.shape.sampleCount()) {
    return makeError("fractal residual holds {} samples, expected {}", code.residual.size(),
                     code.shape.sampleCount());
  }
  return {};
}

}  // namespace tellus::fractal
