#include "tellus/tiles/sample_coding.hpp"

#include <cstring>
#include <memory>

#include <zstd.h>

namespace tellus::coding {

int bytesNeeded(std::span<const std::uint32_t> values) {
  std::uint32_t all = 0;
  for (std::uint32_t v : values) all |= v;
  if (all < (1u << 8)) return 1;
  if (all < (1u << 16)) return 2;
  if (all < (1u << 24)) return 3;
  return 4;
}

void appendBytePlanes(std::span<const std::uint32_t> values, int planes,
                      std::vector<std::byte>& out) {
  const std::size_t start = out.size();
  out.resize(start + values.size() * std::size_t(planes));
  std::byte* dst = out.data() + start;
  for (int p = 0; p < planes; ++p) {
    const unsigned shift = unsigned(8 * p);
    for (std::size_t i = 0; i < values.size(); ++i) *dst++ = std::byte(values[i] >> shift);
  }
}

void readBytePlanes(std::span<const std::byte> bytes, int planes, std::span<std::uint32_t> values) {
  std::fill(values.begin(), values.end(), 0u);
  const std::byte* src = bytes.data();
  for (int p = 0; p < planes; ++p) {
    const unsigned shift = unsigned(8 * p);
    for (std::size_t i = 0; i < values.size(); ++i) {
      values[i] |= std::uint32_t(*src++) << shift;
    }
  }
}

namespace {
struct CCtxDeleter {
  void operator()(ZSTD_CCtx* c) const { ZSTD_freeCCtx(c); }
};
struct DCtxDeleter {
  void operator()(ZSTD_DCtx* d) const { ZSTD_freeDCtx(d); }
};
}  // namespace

Status zstdCompressAppend(std::span<const std::byte> input, int level,
                          std::vector<std::byte>& out) {
  thread_local std::unique_ptr<ZSTD_CCtx, CCtxDeleter> context(ZSTD_createCCtx());
  const std::size_t start = out.size();
  out.resize(start + ZSTD_compressBound(input.size()));
  const std::size_t written = ZSTD_compressCCtx(
      context.get(), out.data() + start, out.size() - start, input.data(), input.size(), level);
  if (ZSTD_isError(written)) {
    out.resize(start);
    return makeError("zstd compression failed: {}", ZSTD_getErrorName(written));
  }
  out.resize(start + written);
  return {};
}

Status zstdDecompressExact(std::span<const std::byte> frame, std::span<std::byte> output) {
  thread_local std::unique_ptr<ZSTD_DCtx, DCtxDeleter> context(ZSTD_createDCtx());
  const unsigned long long declared = ZSTD_getFrameContentSize(frame.data(), frame.size());
  if (declared == ZSTD_CONTENTSIZE_ERROR) return makeError("not a zstd frame");
  if (declared != ZSTD_CONTENTSIZE_UNKNOWN && declared != output.size()) {
    return makeError("zstd frame holds {} bytes, expected {}", declared, output.size());
  }
  const std::size_t got =
      ZSTD_decompressDCtx(context.get(), output.data(), output.size(), frame.data(), frame.size());
  if (ZSTD_isError(got)) return makeError("corrupt zstd data: {}", ZSTD_getErrorName(got));
  if (got != output.size()) {
    return makeError("zstd data holds {} bytes, expected {}", got, output.size());
  }
  return {};
}

Status appendPlanedResiduals(std::span<const std::uint32_t> residuals, int zstdLevel,
                             std::vector<std::byte>& out) {
  const int planes = bytesNeeded(residuals);
  struct PackedTag;
  std::vector<std::byte>& packed = threadScratch<std::byte, PackedTag>(0);
  packed.clear();
  appendBytePlanes(residuals, planes, packed);
  out.push_back(std::byte(planes));
  return zstdCompressAppend(packed, zstdLevel, out);
}

Status readPlanedResiduals(std::span<const std::byte> bytes, std::string_view codec,
                           std::span<std::uint32_t> residuals) {
  if (bytes.empty()) return makeError("{} tile is too short", codec);
  const int planes = int(bytes[0]);
  if (planes < 1 || planes > 4) return makeError("{} tile has {} byte planes", codec, planes);
  struct PackedTag;
  std::vector<std::byte>& packed =
      threadScratch<std::byte, PackedTag>(residuals.size() * std::size_t(planes));
  if (Status s = zstdDecompressExact(bytes.subspan(1), packed); !s) return s;
  readBytePlanes(packed, planes, residuals);
  return {};
}

}  // namespace tellus::coding
