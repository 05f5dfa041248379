#pragma once
// The fractal (PIFS) code of one height tile and its CPU reference decoder (seed 000, section 7).
//
// A tile is padded (edge samples repeated) to a square whose side is a multiple of the largest
// range block and cut into range blocks of r x r samples (a quadtree when several range sizes are
// allowed). Each range R is approximated from a domain block D of 2r x 2r samples elsewhere in
// the tile, shrunk to r x r by averaging 2x2 samples and mapped by one of the eight isometries of
// the square:  R ~ s * (shrink(D) - mean(shrink(D))) + mean(R).
// This is the seed's R ~ s D + o with the offset written as o = mean(R) - s mean(D) (Oien's
// orthogonalised form): the code stores mean(R), which is spatially smooth and entropy-codes far
// better than o, and the first iteration from a flat image already yields every range's mean.
// With domains aligned to the range grid the iteration converges in a few steps.
//
// Decoding iterates the operator from a flat image. All arithmetic is integer, in a fixed-point
// working image (kFractionBits fractional bits, relative to the tile's minimum), so the CPU
// decoder here and the GPU decoder (render/fractal/fractal_gpu_decoder) produce identical values, every
// intermediate fits in 32 bits, and hostile codes cannot overflow.
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "tellus/core/result.hpp"
#include "tellus/tiles/tile_codec.hpp"

namespace tellus::fractal {

inline constexpr int kFractionBits = 4;  // working value = height steps * 16
inline constexpr std::uint32_t kOne = 1u << kFractionBits;
inline constexpr int kScaleBits = 4;       // s = scaleIndex / 16
inline constexpr int kMaxScaleIndex = 15;  // |s| <= 15/16 < 1, so decoding converges
inline constexpr std::int32_t kMaxReliefSteps = (1 << 20) - 1;  // max - min of one tile
inline constexpr std::uint32_t kMaxWorking = std::uint32_t(kMaxReliefSteps) * kOne + (kOne - 1);
inline constexpr int kMinRangeLog2 = 1;  // ranges of 2 x 2 ...
inline constexpr int kMaxRangeLog2 = 4;  // ... to 16 x 16 (sums of 16^2 working values fit uint32)
inline constexpr int kMaxIterations = 32;

struct RangeBlock {
  std::uint16_t x = 0, y = 0;              // top-left sample in the padded tile
  std::uint8_t sizeLog2 = 2;               // side r = 1 << sizeLog2
  std::uint8_t isometry = 0;               // 0..7, see isometryPosition()
  std::int8_t scaleIndex = 0;              // s = scaleIndex / 16; 0 = flat range, no domain
  std::uint16_t domainX = 0, domainY = 0;  // top-left of the 2r x 2r domain block
  std::uint32_t mean = 0;  // mean(R) in working units (height steps above base * 16)
};

struct FractalCode {
  TileShape shape;                 // the tile's samples
  int paddedSide = 0;              // side of the padded square the ranges partition
  std::int32_t base = 0;           // smallest sample of the tile, quantum steps
  int iterations = 0;              // iterations the residual (if any) was computed after
  std::vector<RangeBlock> ranges;  // partition of the padded square
  // Optional residual layer: per sample (shape order) bin index q; the final sample is
  // decoded + q * (2 * residualError + 1), within residualError steps of the source.
  bool hasResidual = false;
  std::uint32_t residualError = 0;
  std::vector<std::int32_t> residual;
  // Optional exact border: the tile's outermost samples (steps above base) in borderLoop order.
  // Neighbouring tiles share their border samples; decoding them exactly makes both tiles agree
  // there, so renderers that read each patch from its own tile draw no cracks. Empty: none.
  std::vector<std::int32_t> border;
};

// The border loop of a tile of w x h samples (w, h >= 2): 2w + 2h - 4 samples, clockwise from
// the top-left corner: the top row left to right, the right column downwards, the bottom row
// right to left, the left column upwards.
inline int borderLength(TileShape shape) {
  return shape.width >= 2 && shape.height >= 2 ? 2 * (shape.width + shape.height) - 4 : 0;
}
// Calls visit(k, x, y) for each sample of the border loop in order, k = 0 .. borderLength - 1.
// (shaders/fractal/publish.comp computes the same k from (x, y).)
template <typename Visit>
void forEachBorderSample(TileShape shape, Visit&& visit) {
  if (borderLength(shape) == 0) return;
  const int w = shape.width - 1, h = shape.height - 1;  // last column and row
  int k = 0;
  for (int x = 0; x < w; ++x) visit(k++, x, 0);  // top row, left to right
  for (int y = 0; y < h; ++y) visit(k++, w, y);  // right column, downwards
  for (int x = w; x > 0; --x) visit(k++, x, h);  // bottom row, right to left
  for (int y = h; y > 0; --y) visit(k++, 0, y);  // left column, upwards
}

// Where pixel (x, y) of an r x r range reads the shrunk domain under isometry k (0..7):
// identity, mirror x, mirror y, rotate 180, transpose, rotate 90, rotate 270, anti-transpose.
inline void isometryPosition(int k, int x, int y, int r, int& u, int& v) {
  const int a = (k & 1) ? r - 1 - x : x;  // bit 0: mirror x
  const int b = (k & 2) ? r - 1 - y : y;  // bit 1: mirror y
  if (k & 4) {                            // bit 2: swap axes
    u = b;
    v = a;
  } else {
    u = a;
    v = b;
  }
}

// The side of the square a tile of `shape` is padded to for ranges up to 2^maxRangeLog2: a
// multiple of the largest range, at least two of them (so every range has a domain twice its
// size).
inline int paddedSideFor(TileShape shape, int maxRangeLog2) {
  const int top = 1 << maxRangeLog2;
  const int blocks = (std::max(shape.width, shape.height) + top - 1) / top;
  return (blocks < 2 ? 2 : blocks) * top;
}

// log2 of a power of two (the smallest k with 2^k >= value).
inline int log2Ceil(int value) {
  int log2 = 0;
  while ((1 << log2) < value) ++log2;
  return log2;
}

// The grid the domain blocks of r x r ranges lie on: step `domainStep` samples, or r when
// domainStep is 0; domainsPerSide positions along each side of the padded square.
inline int domainStepFor(int r, int domainStep) {
  return domainStep > 0 ? domainStep : r;
}
inline int domainsPerSide(int paddedSide, int r, int domainStep) {
  return (paddedSide - 2 * r) / domainStepFor(r, domainStep) + 1;
}

// A flat working image (every value 0): the decoder's starting point.
std::vector<std::uint32_t> flatImage(const FractalCode& code);

// One application of the operator: `out` = T(`in`), both paddedSide^2 working values.
void iterate(const FractalCode& code, std::span<const std::uint32_t> in,
             std::span<std::uint32_t> out);

// The working image after `iterations` applications from a flat image.
std::vector<std::uint32_t> decodeWorking(const FractalCode& code, int iterations);

// Tile samples (quantum steps) from a working image: base + round(value / 16), plus the
// residual when `withResidual` and the code has one; border samples, when the code has them,
// are base + border instead.
void workingToSamples(const FractalCode& code, std::span<const std::uint32_t> working,
                      bool withResidual, std::span<std::int32_t> samples);

// Checks that a code read from untrusted bytes is consistent: ranges inside the padded square,
// partitioning it, domains inside it, scale and mean within limits.
Status validate(const FractalCode& code);

}  // namespace tellus::fractal
