// bounded: lossy with a guaranteed maximum absolute error of e quantum steps per sample
// (near-lossless predictive coding, as JPEG-LS's near-lossless mode). Samples are visited in
// raster order; each is predicted (MED) from already *reconstructed* neighbours, the residual
// is quantised into bins of width 2e+1, and the reconstruction pred + q * (2e+1) is what the
// decoder will see, so |x - reconstruction| <= e for every sample. The bin indices q are
// zigzag-mapped, byte-planed and compressed with zstd. With e = 0 the codec is lossless.
//
// Payload: [u8 version = 1][u32 e, little endian][u8 planes 1..4][zstd frame]
// (the last two parts written by coding::appendPlanedResiduals).
#include <cstring>

#include "tellus/tiles/codecs.hpp"
#include "tellus/tiles/sample_coding.hpp"

namespace tellus {
namespace {

constexpr std::uint8_t kVersion = 1;
constexpr std::size_t kHeaderBytes = 5;

// pred + q * bin, wrapping modulo 2^32 so the decoder of hostile bytes never overflows.
inline std::int32_t reconstruct(std::int32_t predicted, std::int32_t q, std::uint64_t bin) {
  return std::int32_t(std::uint32_t(std::uint64_t(std::uint32_t(predicted)) +
                                    std::uint64_t(std::int64_t(q)) * bin));
}

// Round-to-nearest bin index of residual r for bins of width 2e+1 centred on 0.
inline std::int32_t quantise(std::int64_t r, std::int64_t e) {
  const std::int64_t bin = 2 * e + 1;
  return std::int32_t(r >= 0 ? (r + e) / bin : -((-r + e) / bin));
}

class BoundedCodec final : public TileCodec {
 public:
  BoundedCodec(std::uint32_t maxErrorSteps, int level) : e_(maxErrorSteps), level_(level) {}
  CodecId id() const override { return CodecId::Bounded; }
  std::string_view name() const override { return "bounded"; }
  bool lossless() const override { return e_ == 0; }

  Status encode(std::span<const std::int32_t> samples, TileShape shape,
                std::vector<std::byte>& out) const override {
    if (Status s = coding::checkShape(shape, samples.size()); !s) return s;
    const std::size_t n = samples.size();
    std::vector<std::int32_t>& recon = coding::threadScratch<std::int32_t>(n);
    std::vector<std::uint32_t>& bins = coding::threadScratch<std::uint32_t>(n);
    const std::uint64_t bin = 2 * std::uint64_t(e_) + 1;
    for (int row = 0; row < shape.height; ++row) {
      for (int col = 0; col < shape.width; ++col) {
        const std::size_t i = std::size_t(row) * std::size_t(shape.width) + std::size_t(col);
        const std::int32_t predicted = coding::predictAt(recon.data(), shape.width, col, row);
        const std::int32_t q =
            quantise(std::int64_t(samples[i]) - std::int64_t(predicted), std::int64_t(e_));
        recon[i] = reconstruct(predicted, q, bin);
        bins[i] = coding::zigzag(q);
      }
    }
    out.push_back(std::byte(kVersion));
    std::byte e[4];
    std::memcpy(e, &e_, 4);
    out.insert(out.end(), e, e + 4);
    return coding::appendPlanedResiduals(bins, level_, out);
  }

  Status decode(std::span<const std::byte> bytes, TileShape shape,
                std::span<std::int32_t> samples) const override {
    if (Status s = coding::checkShape(shape, samples.size()); !s) return s;
    if (bytes.size() < kHeaderBytes) return makeError("bounded tile is too short");
    if (std::uint8_t(bytes[0]) != kVersion) {
      return makeError("bounded tile has unknown version {}", std::uint8_t(bytes[0]));
    }
    std::uint32_t e = 0;
    std::memcpy(&e, bytes.data() + 1, 4);
    const std::uint64_t bin = 2 * std::uint64_t(e) + 1;
    std::vector<std::uint32_t>& bins = coding::threadScratch<std::uint32_t>(samples.size());
    if (Status s = coding::readPlanedResiduals(bytes.subspan(kHeaderBytes), "bounded", bins); !s) {
      return s;
    }
    const int w = shape.width;
    std::int32_t* out = samples.data();
    for (int row = 0; row < shape.height; ++row) {
      std::int32_t* line = out + std::ptrdiff_t(row) * w;
      const std::uint32_t* q = bins.data() + std::ptrdiff_t(row) * w;
      for (int col = 0; col < w; ++col) {
        const std::int32_t p = coding::predictAt(out, w, col, row);
        line[col] = reconstruct(p, coding::unzigzag(q[col]), bin);
      }
    }
    return {};
  }

 private:
  std::uint32_t e_;
  int level_;
};

}  // namespace

std::unique_ptr<TileCodec> makeBoundedCodec(const CodecOptions& options) {
  return std::make_unique<BoundedCodec>(options.maxErrorSteps, options.zstdLevel);
}

}  // namespace tellus
