// libFuzzer target: one tile decoder (TELLUS_FUZZ_CODEC names it) on arbitrary bytes, with what
// a store would give it. Input: [width u16][height u16][maxErrorSteps u32][payload]. A side
// below 0xF000 is 1 + (value % 64) samples; above, one of the sides a store's tiles have
// (17 ... 4097; real tiles are 257 x 257 and the seeds include those), so that most runs are
// fast and real sizes are always reachable. maxErrorSteps is anything store metadata may say
// (0..1e9). The decoder must return an error or samples, never crash, read out of bounds or
// allocate without bound.
#include <array>
#include <cstddef>
#include <span>
#include <cstdint>
#include <vector>

#include "fuzz_input.hpp"
#include "tellus/tiles/tile_codec.hpp"

namespace {

int tileSide(std::uint16_t value) {
  static constexpr std::array<int, 9> kStoreSides = {17, 33, 65, 129, 257, 513, 1025, 2049, 4097};
  if (value < 0xF000) return 1 + value % 64;
  return kStoreSides[value % kStoreSides.size()];
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  tellus::fuzz::FuzzInput input(data, size);
  const int width = tileSide(input.take<std::uint16_t>());
  const int height = tileSide(input.take<std::uint16_t>());
  const std::uint32_t maxErrorSteps = input.take<std::uint32_t>() % 1'000'000'001u;
  auto codec = tellus::makeCodec(TELLUS_FUZZ_CODEC, {.maxErrorSteps = maxErrorSteps});
  if (!codec) return 0;
  const tellus::TileShape shape{width, height};
  // One buffer for all runs: the decoder's own allocations are what is being tested.
  static std::vector<std::int32_t> buffer;
  if (buffer.size() < shape.sampleCount()) buffer.resize(shape.sampleCount());
  (void)codec.value()->decode(input.rest(), shape,
                              std::span(buffer.data(), shape.sampleCount()));
  return 0;
}
