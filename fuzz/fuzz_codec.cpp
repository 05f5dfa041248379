// libFuzzer target: one tile decoder (TELLUS_FUZZ_CODEC names it) on arbitrary bytes. The first
// two bytes pick the tile shape (1..64 x 1..64), the rest is the payload. The decoder must
// return an error or samples, never crash, read out of bounds or allocate without bound.
#include <cstddef>
#include <cstdint>
#include <vector>

#include "tellus/tiles/tile_codec.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const auto codec =
      tellus::makeCodec(TELLUS_FUZZ_CODEC, {.maxErrorSteps = 3, .zstdLevel = 3});
  if (size < 2) return 0;
  const tellus::TileShape shape{1 + data[0] % 64, 1 + data[1] % 64};
  std::vector<std::int32_t> samples(shape.sampleCount());
  const std::span<const std::byte> payload(reinterpret_cast<const std::byte*>(data + 2), size - 2);
  (void)codec.value()->decode(payload, shape, samples);
  return 0;
}
