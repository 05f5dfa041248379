// raw: samples as little-endian int32, no compression. The baseline every codec is measured
// against, and the fastest to decode.
#include <cstring>

#include "tellus/tiles/codecs.hpp"
#include "tellus/tiles/sample_coding.hpp"

namespace tellus {
namespace {

class RawCodec final : public TileCodec {
 public:
  CodecId id() const override { return CodecId::Raw; }
  std::string_view name() const override { return "raw"; }
  bool lossless() const override { return true; }

  Status encode(std::span<const std::int32_t> samples, TileShape shape,
                std::vector<std::byte>& out) const override {
    if (Status s = coding::checkShape(shape, samples.size()); !s) return s;
    const std::size_t start = out.size();
    out.resize(start + samples.size_bytes());
    std::memcpy(out.data() + start, samples.data(), samples.size_bytes());
    return {};
  }

  Status decode(std::span<const std::byte> bytes, TileShape shape,
                std::span<std::int32_t> samples) const override {
    if (Status s = coding::checkShape(shape, samples.size()); !s) return s;
    if (bytes.size() != samples.size_bytes()) {
      return makeError("raw tile has {} bytes, expected {}", bytes.size(), samples.size_bytes());
    }
    std::memcpy(samples.data(), bytes.data(), bytes.size());
    return {};
  }
};

}  // namespace

std::unique_ptr<TileCodec> makeRawCodec() {
  return std::make_unique<RawCodec>();
}

}  // namespace tellus
