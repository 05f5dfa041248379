#pragma once
// Building blocks shared by the predictive codecs (zstd, bounded): the MED predictor, zigzag
// mapping of signed residuals, byte-plane packing and zstd with per-thread contexts.
//
// Arithmetic on samples wraps modulo 2^32 (done in uint32), so encoder and decoder agree
// bit-for-bit on any input and hostile bytes cannot cause signed overflow.
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <span>
#include <string_view>
#include <vector>

#include "tellus/core/result.hpp"
#include "tellus/tiles/tile_codec.hpp"

namespace tellus::coding {

// Median edge detector (LOCO-I / JPEG-LS): predicts x from left a, up b, up-left c.
inline std::int32_t predictMed(std::int32_t a, std::int32_t b, std::int32_t c) {
  const std::int32_t lo = std::min(a, b), hi = std::max(a, b);
  if (c >= hi) return lo;
  if (c <= lo) return hi;
  return std::int32_t(std::uint32_t(a) + std::uint32_t(b) - std::uint32_t(c));
}

// Prediction of sample (col, row) from already known neighbours in `values` (row-major,
// `width` per row): MED inside, left neighbour on the first row, up neighbour on the first
// column, 0 for the first sample.
inline std::int32_t predictAt(const std::int32_t* values, int width, int col, int row) {
  const std::int32_t* here = values + std::ptrdiff_t(row) * width + col;
  if (row == 0) return col == 0 ? 0 : here[-1];
  if (col == 0) return here[-width];
  return predictMed(here[-1], here[-width], here[-width - 1]);
}

inline std::uint32_t zigzag(std::int32_t v) {
  return (std::uint32_t(v) << 1) ^ std::uint32_t(v >> 31);
}
inline std::int32_t unzigzag(std::uint32_t u) {
  return std::int32_t((u >> 1) ^ (~(u & 1u) + 1u));
}

// Smallest number of bytes (1..4) that holds every value.
int bytesNeeded(std::span<const std::uint32_t> values);

// Appends `planes` byte planes of `values` to out: all lowest bytes, then all second bytes...
void appendBytePlanes(std::span<const std::uint32_t> values, int planes,
                      std::vector<std::byte>& out);
// Inverse of appendBytePlanes: `bytes` holds values.size() * planes bytes.
void readBytePlanes(std::span<const std::byte> bytes, int planes, std::span<std::uint32_t> values);

// Appends one zstd frame holding `input` to out.
Status zstdCompressAppend(std::span<const std::byte> input, int level, std::vector<std::byte>& out);
// Decompresses one zstd frame that must expand to exactly output.size() bytes.
Status zstdDecompressExact(std::span<const std::byte> frame, std::span<std::byte> output);

// Appends [u8 planes 1..4][zstd frame of the residuals' byte planes] to out, using as few
// planes as the largest residual needs. The predictive codecs' common payload tail.
Status appendPlanedResiduals(std::span<const std::uint32_t> residuals, int zstdLevel,
                             std::vector<std::byte>& out);
// Inverse of appendPlanedResiduals: `bytes` is the tail, `residuals` gets exactly its size.
// `codec` names the codec in error messages.
Status readPlanedResiduals(std::span<const std::byte> bytes, std::string_view codec,
                           std::span<std::uint32_t> residuals);

// A per-thread scratch vector, reused across calls to avoid allocating per tile. Each (T, Tag)
// pair is a separate vector: callers that hold one while calling code that uses another pick
// distinct tags.
template <typename T, typename Tag = void>
std::vector<T>& threadScratch(std::size_t size) {
  thread_local std::vector<T> scratch;
  scratch.resize(size);
  return scratch;
}

}  // namespace tellus::coding

namespace tellus::coding {

// Largest tile side a codec accepts (samples); protects decoders from absurd shapes.
inline constexpr int kMaxTileSide = 16385;

// Checks that `shape` is sane and `count` samples match it.
inline Status checkShape(TileShape shape, std::size_t count) {
  if (shape.width < 1 || shape.height < 1 || shape.width > kMaxTileSide ||
      shape.height > kMaxTileSide) {
    return makeError("invalid tile shape {}x{}", shape.width, shape.height);
  }
  if (count != shape.sampleCount()) {
    return makeError("buffer of {} samples for a {}x{} tile", count, shape.width, shape.height);
  }
  return {};
}

}  // namespace tellus::coding
