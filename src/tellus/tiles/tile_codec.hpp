#pragma once
// The tile codec interface: every height codec (raw, zstd, bounded, lerc, and later fractal)
// turns one tile of integer height samples into bytes and back.
//
// Samples are int32 counts of the store's vertical quantum (metres per step, see
// StoreMetadata::quantumM), row by row, row 0 = north. Buffers are owned by the caller: encode()
// appends to a caller's byte vector, decode() fills a caller's sample span. Decoders treat their
// input as untrusted: any byte sequence yields either the samples or an Error, never a crash,
// an overread or an unbounded allocation (each decoder has a libFuzzer target).
#include <cstddef>
#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "tellus/core/result.hpp"

namespace tellus {

// Stable on-disk identifiers: never renumber.
enum class CodecId : std::uint32_t { Raw = 0, Zstd = 1, Bounded = 2, Lerc = 3, Fractal = 4 };

struct TileShape {
  int width = 0;   // samples per row
  int height = 0;  // rows
  std::size_t sampleCount() const { return std::size_t(width) * std::size_t(height); }
};

// Parameters of the fractal (PIFS) codec (tiles/fractal_code.hpp explains the code).
struct FractalOptions {
  int rangeSize = 4;            // side of the smallest range block: 2, 4, 8 or 16 samples
  int quadtreeLevels = 1;       // 1: fixed ranges; n: ranges of rangeSize << (n - 1) split down
  double splitRmseSteps = 2.0;  // quadtree: a range whose fit RMSE (steps) exceeds this splits
  double flatRmseSteps = 0.5;   // ranges this close (RMS, steps) to their mean are coded flat
  int domainStep = 0;           // domain grid step, samples, even; 0 = the range's size
  int candidates = 4;           // nearest neighbours per sign examined in the domain search
  bool fullSearch = false;      // scan every domain (the seed's method; slow) instead
  // Adds the residual layer: |decoded - input| <= CodecOptions::maxErrorSteps on every sample.
  bool residual = false;
  int iterations = 0;  // decoder iterations the code is made for; 0 = until stable (max 16)
  // Codes the tile's outermost samples exactly (about 600 bytes for 257 x 257), so neighbouring
  // tiles agree on the samples they share and renderers draw no cracks between them.
  bool exactBorder = true;
};

// The zstd level builds use unless told otherwise: GDAL's default (ZSTD_LEVEL=9). After the
// MED prediction and byte planes, level 12 makes stores only 0.06 % (SRTM) to 0.4 % (float
// terrain) smaller for 1.3 to 2 times the compression time (docs/globe.md, "Build speed").
inline constexpr int kDefaultZstdLevel = 9;

struct CodecOptions {
  // Largest allowed |decoded - input| per sample, in quantum steps. Lossless codecs ignore it.
  std::uint32_t maxErrorSteps = 0;
  // zstd compression level for the codecs that use zstd (1..22); decoding speed does not depend
  // on it.
  int zstdLevel = kDefaultZstdLevel;
  FractalOptions fractal{};
};

class TileCodec {
 public:
  virtual ~TileCodec() = default;
  virtual CodecId id() const = 0;
  virtual std::string_view name() const = 0;
  // True when decode(encode(x)) == x for every x; false when only maxErrorSteps is guaranteed.
  virtual bool lossless() const = 0;
  // True when every decoded sample is within CodecOptions::maxErrorSteps of the input (always
  // for the lossless and error-bounded codecs; not for the fractal codec without residual).
  virtual bool boundsError() const { return true; }

  // Appends the encoding of `samples` (shape.sampleCount() values) to `out`.
  virtual Status encode(std::span<const std::int32_t> samples, TileShape shape,
                        std::vector<std::byte>& out) const = 0;
  // Decodes `bytes` into `samples`, which must hold exactly shape.sampleCount() values. Fails
  // with a message (no tile name: the caller adds it) when the bytes are not a valid encoding of
  // a tile of that shape.
  virtual Status decode(std::span<const std::byte> bytes, TileShape shape,
                        std::span<std::int32_t> samples) const = 0;
};

// Creates a codec; `name` is one of codecNames(). Errors name the valid choices.
Result<std::unique_ptr<TileCodec>> makeCodec(std::string_view name, const CodecOptions& options);
Result<std::unique_ptr<TileCodec>> makeCodec(CodecId id, const CodecOptions& options);
const std::vector<std::string>& codecNames();
std::string_view codecName(CodecId id);

}  // namespace tellus
