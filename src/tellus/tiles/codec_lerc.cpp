// lerc: Esri's Limited Error Raster Compression (liblerc), at the same maximum error as the
// bounded codec (maxErrorSteps quantum steps; 0 = lossless). A yardstick and an option for
// interoperability. The payload is one LERC blob of int32 samples.
#include <Lerc_c_api.h>

#include <array>
#include <cstdint>
#include <limits>

#include "tellus/tiles/codecs.hpp"
#include "tellus/tiles/sample_coding.hpp"

namespace tellus {
namespace {

constexpr unsigned kLercInt = 4;  // LERC data type code for int32

// The LERC format version this liblerc writes for Tellus tiles (found once by encoding a tiny
// tile; 6 for Debian's liblerc 4.0). A blob of any other version is refused: LERC's checksum
// does not cover the version field, and liblerc 4.0 reading a version-6 blob whose version
// field says 4 (another header layout) dereferences null (found by fuzz_decode_lerc, kept in
// fuzz/corpus/fuzz_decode_lerc). A store written by a liblerc that writes another version must
// be rebuilt; the error says so.
unsigned writtenLercVersion() {
  static const unsigned version = [] {
    const std::array<std::int32_t, 4> tile = {1, 2, 3, 4};
    std::array<unsigned char, 256> blob{};
    unsigned written = 0;
    if (lerc_encode(tile.data(), kLercInt, 1, 2, 2, 1, 0, nullptr, 0.5, blob.data(),
                    unsigned(blob.size()), &written) != 0) {
      return 0u;
    }
    unsigned info[11] = {};
    double ranges[3] = {};
    if (lerc_getBlobInfo(blob.data(), written, info, ranges, 11, 3) != 0) return 0u;
    return info[0];
  }();
  return version;
}

class LercCodec final : public TileCodec {
 public:
  explicit LercCodec(std::uint32_t maxErrorSteps) : e_(maxErrorSteps) {}
  CodecId id() const override { return CodecId::Lerc; }
  std::string_view name() const override { return "lerc"; }
  bool lossless() const override { return e_ == 0; }

  Status encode(std::span<const std::int32_t> samples, TileShape shape,
                std::vector<std::byte>& out) const override {
    if (Status s = coding::checkShape(shape, samples.size()); !s) return s;
    // LERC treats maxZErr 0.5 as lossless for integer data.
    const double maxZErr = e_ == 0 ? 0.5 : double(e_);
    unsigned size = 0;
    if (lerc_computeCompressedSize(samples.data(), kLercInt, 1, shape.width, shape.height, 1, 0,
                                   nullptr, maxZErr, &size) != 0) {
      return makeError("LERC could not size the tile");
    }
    const std::size_t start = out.size();
    out.resize(start + size);
    unsigned written = 0;
    if (lerc_encode(samples.data(), kLercInt, 1, shape.width, shape.height, 1, 0, nullptr, maxZErr,
                    reinterpret_cast<unsigned char*>(out.data() + start), size, &written) != 0) {
      out.resize(start);
      return makeError("LERC could not encode the tile");
    }
    out.resize(start + written);
    return {};
  }

  Status decode(std::span<const std::byte> bytes, TileShape shape,
                std::span<std::int32_t> samples) const override {
    if (Status s = coding::checkShape(shape, samples.size()); !s) return s;
    if (bytes.size() > std::numeric_limits<unsigned>::max()) return makeError("LERC blob too big");
    const auto* blob = reinterpret_cast<const unsigned char*>(bytes.data());
    const auto blobSize = unsigned(bytes.size());
    // Check what the blob declares before letting LERC write into our buffer.
    unsigned info[11] = {};
    double ranges[3] = {};
    if (lerc_getBlobInfo(blob, blobSize, info, ranges, 11, 3) != 0) {
      return makeError("not a LERC blob");
    }
    const unsigned version = info[0], type = info[1], depth = info[2], cols = info[3],
                   rows = info[4], bands = info[5], validSamples = info[6], declaredSize = info[7];
    if (version != writtenLercVersion()) {
      return makeError(
          "LERC blob of version {}; this liblerc writes and reads version {} (rebuild the "
          "store if it was written by another liblerc)",
          version, writtenLercVersion());
    }
    if (type != kLercInt || depth != 1 || bands != 1 || int(cols) != shape.width ||
        int(rows) != shape.height || declaredSize > blobSize) {
      return makeError("LERC blob holds a {}x{}x{} tile of type {}, expected {}x{} int32", cols,
                       rows, bands, type, shape.width, shape.height);
    }
    // Tellus never writes invalid samples, so a blob must declare every sample valid (which
    // also keeps liblerc off its mask-reuse path, where damaged blobs read uninitialised
    // memory; fixed upstream after 4.1.1).
    if (validSamples != cols * rows) {
      return makeError("LERC blob declares {} of its {} samples valid; Tellus tiles have no "
                       "invalid samples",
                       validSamples, cols * rows);
    }
    if (lerc_decode(blob, blobSize, 0, nullptr, 1, shape.width, shape.height, 1, kLercInt,
                    samples.data()) != 0) {
      return makeError("corrupt LERC blob");
    }
    return {};
  }

 private:
  std::uint32_t e_;
};

}  // namespace

std::unique_ptr<TileCodec> makeLercCodec(const CodecOptions& options) {
  return std::make_unique<LercCodec>(options.maxErrorSteps);
}

}  // namespace tellus
