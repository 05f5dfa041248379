// The codecs: lossless ones round-trip exactly, lossy ones respect their bound on every sample,
// on real SRTM tiles and on adversarial synthetic ones; decoders reject bad bytes cleanly.
#include <algorithm>
#include <fstream>
#include <iterator>
#include <random>

#include <gtest/gtest.h>

#include "support/test_support.hpp"
#include "tellus/dem/dem_loader.hpp"
#include "tellus/tiles/tile_codec.hpp"

namespace tellus {
namespace {

constexpr TileShape kShape{257, 257};

using Tile = std::vector<std::int32_t>;

// 257x257 tiles cut from a real SRTM file (integer metres), at several places.
std::vector<Tile> realTiles(const std::filesystem::path& data) {
  Result<HeightGrid> grid = loadDem({data / "srtm3-hgt-east-asia/N36E137.hgt"});  // Japan Alps
  EXPECT_TRUE(grid) << grid.error().message;
  std::vector<Tile> tiles;
  for (int origin : {0, 300, 944}) {
    Tile tile(kShape.sampleCount());
    for (int j = 0; j < kShape.height; ++j) {
      for (int i = 0; i < kShape.width; ++i) {
        tile[std::size_t(j * kShape.width + i)] = std::int32_t(grid->at(origin + i, origin + j));
      }
    }
    tiles.push_back(std::move(tile));
  }
  return tiles;
}

// Tiles that stress the arithmetic: white noise over the whole int32 range, a constant, and
// steps between the extremes.
std::vector<Tile> adversarialTiles() {
  std::mt19937 random(7);
  Tile noise(kShape.sampleCount()), constant(kShape.sampleCount(), -12345),
      steps(kShape.sampleCount());
  std::uniform_int_distribution<std::int32_t> any(std::numeric_limits<std::int32_t>::min(),
                                                  std::numeric_limits<std::int32_t>::max());
  for (auto& v : noise) v = any(random);
  for (std::size_t i = 0; i < steps.size(); ++i) {
    steps[i] = (i / 17) % 2 ? std::numeric_limits<std::int32_t>::max() - 3
                            : std::numeric_limits<std::int32_t>::min() + 3;
  }
  return {noise, constant, steps};
}

std::int64_t maxAbsDifference(const Tile& a, const Tile& b) {
  std::int64_t worst = 0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    worst = std::max(worst, std::abs(std::int64_t(a[i]) - std::int64_t(b[i])));
  }
  return worst;
}

Tile roundTrip(const TileCodec& codec, const Tile& tile, std::size_t* bytes = nullptr) {
  std::vector<std::byte> encoded;
  const Status encodedOk = codec.encode(tile, kShape, encoded);
  EXPECT_TRUE(encodedOk) << encodedOk.error().message;
  if (bytes) *bytes = encoded.size();
  Tile decoded(tile.size(), 0);
  const Status decodedOk = codec.decode(encoded, kShape, decoded);
  EXPECT_TRUE(decodedOk) << decodedOk.error().message;
  return decoded;
}

TEST(TileCodec, LosslessCodecsRoundTripRealTilesExactly) {
  TELLUS_REQUIRE_SHARED_DATA(data);
  for (const char* name : {"raw", "zstd", "bounded", "lerc"}) {
    auto codec = makeCodec(
        name, {.maxErrorSteps = 0, .zstdLevel = 12});  // bound 0: bounded and lerc are lossless too
    ASSERT_TRUE(codec);
    for (const Tile& tile : realTiles(data)) {
      std::size_t bytes = 0;
      EXPECT_EQ(roundTrip(*codec.value(), tile, &bytes), tile) << name;
      if (std::string(name) != "raw") {
        EXPECT_LT(bytes, tile.size() * 2) << name << " barely compresses";
      }
    }
  }
}

TEST(TileCodec, LosslessCodecsRoundTripAdversarialTilesExactly) {
  for (const char* name : {"raw", "zstd", "bounded"}) {
    auto codec = makeCodec(name, {.maxErrorSteps = 0, .zstdLevel = 3});
    ASSERT_TRUE(codec);
    for (const Tile& tile : adversarialTiles())
      EXPECT_EQ(roundTrip(*codec.value(), tile), tile) << name;
  }
}

TEST(TileCodec, LossyCodecsRespectTheBoundOnEverySample) {
  TELLUS_REQUIRE_SHARED_DATA(data);
  const std::vector<Tile> tiles = realTiles(data);
  for (const char* name : {"bounded", "lerc"}) {
    for (std::uint32_t bound : {1u, 2u, 5u, 20u}) {
      auto codec = makeCodec(name, {.maxErrorSteps = bound, .zstdLevel = 12});
      ASSERT_TRUE(codec);
      EXPECT_FALSE(codec.value()->lossless());
      std::int64_t worst = 0;
      for (const Tile& tile : tiles)
        worst = std::max(worst, maxAbsDifference(roundTrip(*codec.value(), tile), tile));
      EXPECT_LE(worst, std::int64_t(bound)) << name << " at bound " << bound;
      EXPECT_GE(worst, std::int64_t(bound) / 2) << name << " does not use its error budget";
    }
  }
}

TEST(TileCodec, BoundedHoldsOnAdversarialTiles) {
  auto codec = makeCodec("bounded", {.maxErrorSteps = 7, .zstdLevel = 3});
  ASSERT_TRUE(codec);
  for (const Tile& tile : adversarialTiles()) {
    EXPECT_LE(maxAbsDifference(roundTrip(*codec.value(), tile), tile), 7);
  }
}

TEST(TileCodec, BoundedAtOneMetreIsSmallerThanLercAtOneMetre) {
  TELLUS_REQUIRE_SHARED_DATA(data);
  std::size_t boundedBytes = 0, lercBytes = 0;
  auto bounded = makeCodec("bounded", {.maxErrorSteps = 1, .zstdLevel = 12});
  auto lerc = makeCodec("lerc", {.maxErrorSteps = 1, .zstdLevel = 12});
  for (const Tile& tile : realTiles(data)) {
    std::size_t b = 0;
    roundTrip(*bounded.value(), tile, &b);
    boundedBytes += b;
    roundTrip(*lerc.value(), tile, &b);
    lercBytes += b;
  }
  EXPECT_LT(boundedBytes, lercBytes);
}

TEST(TileCodec, DecodersRejectTruncatedAndGarbledBytes) {
  const Tile tile = adversarialTiles()[1];
  std::mt19937 random(11);
  for (const char* name : {"raw", "zstd", "bounded", "lerc", "fractal"}) {
    auto codec = makeCodec(name, {.maxErrorSteps = 2, .zstdLevel = 3});
    ASSERT_TRUE(codec);
    std::vector<std::byte> encoded;
    ASSERT_TRUE(codec.value()->encode(tile, kShape, encoded));
    Tile out(tile.size());
    // Every truncation fails.
    for (std::size_t size :
         {std::size_t(0), std::size_t(1), encoded.size() / 2, encoded.size() - 1}) {
      EXPECT_FALSE(codec.value()->decode(std::span(encoded).first(size), kShape, out))
          << name << " accepted " << size << " of " << encoded.size() << " bytes";
    }
    // Random bytes never crash (they may decode to something for raw).
    std::vector<std::byte> garbage(encoded.size());
    for (auto& b : garbage) b = std::byte(random());
    (void)codec.value()->decode(garbage, kShape, out);
    // A wrong shape is refused.
    EXPECT_FALSE(codec.value()->decode(encoded, {256, 257}, std::span(out).first(256 * 257)));
    EXPECT_FALSE(codec.value()->decode(encoded, kShape, std::span(out).first(10)));
  }
}

// liblerc 4.0 dereferences null when a blob's version field (which LERC's checksum does not
// cover) is changed to an older layout. fuzz_decode_lerc found two such blobs (kept in its
// regression corpus, behind the fuzzer's 8 bytes of shape and options); they are refused
// before liblerc decodes them, as is every other version than the one liblerc writes.
TEST(TileCodec, LercRefusesABlobWhoseVersionWasChanged) {
  auto codec = makeCodec("lerc", {.maxErrorSteps = 3});
  ASSERT_TRUE(codec);
  for (const char* name : {"version-6-read-as-4-a", "version-6-read-as-4-b"}) {
    std::ifstream in(std::filesystem::path(TELLUS_FUZZ_CORPUS_DIR) / "fuzz_decode_lerc" / name,
                     std::ios::binary);
    const std::vector<char> bytes((std::istreambuf_iterator<char>(in)),
                                  std::istreambuf_iterator<char>());
    ASSERT_GT(bytes.size(), 8u) << name;
    const TileShape shape{1 + (std::uint8_t(bytes[0]) | std::uint8_t(bytes[1]) << 8) % 64,
                          1 + (std::uint8_t(bytes[2]) | std::uint8_t(bytes[3]) << 8) % 64};
    Tile out(shape.sampleCount());
    const auto blob = std::as_bytes(std::span(bytes)).subspan(8);
    Status decoded = codec.value()->decode(blob, shape, out);
    ASSERT_FALSE(decoded) << name;
    EXPECT_NE(decoded.error().message.find("LERC blob of version 4"), std::string::npos)
        << decoded.error().message;
  }
  const Tile tile = adversarialTiles()[1];
  std::vector<std::byte> encoded;
  ASSERT_TRUE(codec.value()->encode(tile, kShape, encoded));
  Tile out(tile.size());
  const std::size_t versionOffset = 6;  // after "Lerc2 "
  for (std::uint8_t version = 2; version <= 7; ++version) {
    if (std::byte(version) == encoded[versionOffset]) continue;
    std::vector<std::byte> changed = encoded;
    changed[versionOffset] = std::byte(version);
    EXPECT_FALSE(codec.value()->decode(changed, kShape, out)) << "version " << int(version);
  }
  EXPECT_TRUE(codec.value()->decode(encoded, kShape, out));
}

TEST(TileCodec, UnknownNamesListTheChoices) {
  auto codec = makeCodec("jpeg", {});
  ASSERT_FALSE(codec);
  EXPECT_NE(codec.error().message.find("raw, zstd, bounded, lerc"), std::string::npos);
}

}  // namespace
}  // namespace tellus
