// fractal: partitioned iterated function system (PIFS) coding of height tiles, seed 000
// section 7 (fractal_code.hpp explains the code, fractal_encoder.hpp the search,
// fractal_format.hpp the payload). Without the residual layer the codec bounds nothing; with it
// every sample is within CodecOptions::maxErrorSteps of the input after the code's iterations.
#include "tellus/tiles/codecs.hpp"
#include "tellus/tiles/fractal_encoder.hpp"
#include "tellus/tiles/fractal_format.hpp"
#include "tellus/tiles/sample_coding.hpp"

namespace tellus {
namespace {

class FractalCodec final : public TileCodec {
 public:
  explicit FractalCodec(const CodecOptions& options) : options_(options) {}
  CodecId id() const override { return CodecId::Fractal; }
  std::string_view name() const override { return "fractal"; }
  bool lossless() const override { return false; }
  bool boundsError() const override { return options_.fractal.residual; }

  Status encode(std::span<const std::int32_t> samples, TileShape shape,
                std::vector<std::byte>& out) const override {
    if (Status s = coding::checkShape(shape, samples.size()); !s) return s;
    const FractalOptions& o = options_.fractal;
    Result<fractal::FractalCode> code = fractal::encode(samples, shape, o, options_.maxErrorSteps);
    if (!code) return code.error();
    const int minLog2 = fractal::log2Ceil(o.rangeSize);
    return fractal::write(code.value(), minLog2, minLog2 + o.quadtreeLevels - 1, o.domainStep,
                          options_.zstdLevel, out);
  }

  Status decode(std::span<const std::byte> bytes, TileShape shape,
                std::span<std::int32_t> samples) const override {
    if (Status s = coding::checkShape(shape, samples.size()); !s) return s;
    Result<fractal::FractalCode> code = fractal::read(bytes, shape);
    if (!code) return code.error();
    const std::vector<std::uint32_t> working =
        fractal::decodeWorking(code.value(), code->iterations);
    fractal::workingToSamples(code.value(), working, true, samples);
    return {};
  }

 private:
  CodecOptions options_;
};

}  // namespace

std::unique_ptr<TileCodec> makeFractalCodec(const CodecOptions& options) {
  return std::make_unique<FractalCodec>(options);
}

}  // namespace tellus
