// zstd: lossless. Each sample is predicted from its decoded neighbours with the median edge
// detector (MED, as in JPEG-LS); the residuals are zigzag-mapped to unsigned, split into byte
// planes (all low bytes, then the next bytes...) using only as many planes as the largest
// residual needs, and compressed with zstd.
//
// Payload: [u8 version = 1][u8 planes 1..4][zstd frame of sampleCount * planes bytes]
// (the last two parts written by coding::appendPlanedResiduals).
#include "tellus/tiles/codecs.hpp"
#include "tellus/tiles/sample_coding.hpp"

namespace tellus {
namespace {

constexpr std::uint8_t kVersion = 1;
constexpr std::size_t kHeaderBytes = 1;

class ZstdCodec final : public TileCodec {
 public:
  explicit ZstdCodec(int level) : level_(level) {}
  CodecId id() const override { return CodecId::Zstd; }
  std::string_view name() const override { return "zstd"; }
  bool lossless() const override { return true; }

  Status encode(std::span<const std::int32_t> samples, TileShape shape,
                std::vector<std::byte>& out) const override {
    if (Status s = coding::checkShape(shape, samples.size()); !s) return s;
    std::vector<std::uint32_t>& residuals = coding::threadScratch<std::uint32_t>(samples.size());
    for (int row = 0; row < shape.height; ++row) {
      for (int col = 0; col < shape.width; ++col) {
        const std::size_t i = std::size_t(row) * std::size_t(shape.width) + std::size_t(col);
        const std::int32_t predicted = coding::predictAt(samples.data(), shape.width, col, row);
        residuals[i] =
            coding::zigzag(std::int32_t(std::uint32_t(samples[i]) - std::uint32_t(predicted)));
      }
    }
    out.push_back(std::byte(kVersion));
    return coding::appendPlanedResiduals(residuals, level_, out);
  }

  Status decode(std::span<const std::byte> bytes, TileShape shape,
                std::span<std::int32_t> samples) const override {
    if (Status s = coding::checkShape(shape, samples.size()); !s) return s;
    if (bytes.size() < kHeaderBytes) return makeError("zstd tile is too short");
    if (std::uint8_t(bytes[0]) != kVersion) {
      return makeError("zstd tile has unknown version {}", std::uint8_t(bytes[0]));
    }
    std::vector<std::uint32_t>& residuals = coding::threadScratch<std::uint32_t>(samples.size());
    if (Status s = coding::readPlanedResiduals(bytes.subspan(kHeaderBytes), "zstd", residuals);
        !s) {
      return s;
    }
    const int w = shape.width;
    std::int32_t* out = samples.data();
    // First row: left prediction. Then each row: up for the first column, MED for the rest.
    out[0] = coding::unzigzag(residuals[0]);
    for (int col = 1; col < w; ++col) {
      out[col] = std::int32_t(std::uint32_t(out[col - 1]) +
                              std::uint32_t(coding::unzigzag(residuals[std::size_t(col)])));
    }
    for (int row = 1; row < shape.height; ++row) {
      std::int32_t* line = out + std::ptrdiff_t(row) * w;
      const std::int32_t* up = line - w;
      const std::uint32_t* r = residuals.data() + std::ptrdiff_t(row) * w;
      line[0] = std::int32_t(std::uint32_t(up[0]) + std::uint32_t(coding::unzigzag(r[0])));
      for (int col = 1; col < w; ++col) {
        const std::int32_t p = coding::predictMed(line[col - 1], up[col], up[col - 1]);
        line[col] = std::int32_t(std::uint32_t(p) + std::uint32_t(coding::unzigzag(r[col])));
      }
    }
    return {};
  }

 private:
  int level_;
};

}  // namespace

std::unique_ptr<TileCodec> makeZstdCodec(const CodecOptions& options) {
  return std::make_unique<ZstdCodec>(options.zstdLevel);
}

}  // namespace tellus
