// The fractal (PIFS) codec on the CPU: the code converges from a flat image, the residual layer
// bounds the error on every sample, the nearest-neighbour search is as good as the seed's full
// scan, the quadtree splits where the fit is poor, and bad payloads or options are refused.
#include <algorithm>
#include <cmath>

#include <gtest/gtest.h>

#include "support/test_support.hpp"
#include "tellus/dem/dem_loader.hpp"
#include "tellus/tiles/fractal_encoder.hpp"
#include "tellus/tiles/fractal_format.hpp"
#include "tellus/tiles/tile_codec.hpp"

namespace tellus {
namespace {

using Tile = std::vector<std::int32_t>;

// A side x side tile of a real SRTM file (integer metres) at (origin, origin); origins from
// 600 on lie in the Japan Alps.
Tile realTile(const std::filesystem::path& data, int side, int origin) {
  Result<HeightGrid> grid = loadDem({data / "srtm3-hgt-east-asia/N36E137.hgt"});
  EXPECT_TRUE(grid) << grid.error().message;
  Tile tile(std::size_t(side) * std::size_t(side));
  for (int j = 0; j < side; ++j) {
    for (int i = 0; i < side; ++i) {
      tile[std::size_t(j * side + i)] = std::int32_t(grid->at(origin + i, origin + j));
    }
  }
  return tile;
}

double rmse(const Tile& a, const Tile& b) {
  double sum = 0.0;
  for (std::size_t i = 0; i < a.size(); ++i) sum += double(a[i] - b[i]) * double(a[i] - b[i]);
  return std::sqrt(sum / double(a.size()));
}

std::int64_t maxAbs(const Tile& a, const Tile& b) {
  std::int64_t worst = 0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    worst = std::max(worst, std::abs(std::int64_t(a[i]) - std::int64_t(b[i])));
  }
  return worst;
}

Tile decodeAfter(const fractal::FractalCode& code, int iterations) {
  Tile out(code.shape.sampleCount());
  fractal::workingToSamples(code, fractal::decodeWorking(code, iterations), false, out);
  return out;
}

TEST(FractalCodec, ConvergesFromAFlatImageInAFewIterations) {
  TELLUS_REQUIRE_SHARED_DATA(data);
  const TileShape shape{257, 257};
  const Tile tile = realTile(data, 257, 750);
  const auto code = fractal::encode(tile, shape, {}, 0);
  ASSERT_TRUE(code) << code.error().message;
  EXPECT_EQ(code->ranges.size(), 65u * 65u);  // 260 / 4 ranges per side
  // Iteration 1 from flat gives every range its mean; later ones add the domains' detail.
  std::vector<double> errors;
  for (int k = 1; k <= 8; ++k) errors.push_back(rmse(decodeAfter(code.value(), k), tile));
  EXPECT_GT(errors[0], 2.0 * errors[3]);
  EXPECT_LE(code->iterations, 8);
  const double converged = rmse(decodeAfter(code.value(), code->iterations), tile);
  for (int k = code->iterations; k <= 8; ++k) {
    EXPECT_NEAR(errors[std::size_t(k - 1)], converged, 0.05) << "iteration " << k;
  }
  // Alpine SRTM3 at 4x4 ranges: a few metres, far below the tile's 2000 m relief.
  EXPECT_LT(converged, 15.0);
}

TEST(FractalCodec, TheFirstIterationIsTheRangeMeans) {
  TELLUS_REQUIRE_SHARED_DATA(data);
  const Tile tile = realTile(data, 33, 800);
  const auto code = fractal::encode(tile, {33, 33}, {}, 0);
  ASSERT_TRUE(code);
  const std::vector<std::uint32_t> once = fractal::decodeWorking(code.value(), 1);
  for (const fractal::RangeBlock& range : code->ranges) {
    for (int y = range.y; y < range.y + (1 << range.sizeLog2); ++y) {
      for (int x = range.x; x < range.x + (1 << range.sizeLog2); ++x) {
        ASSERT_EQ(once[std::size_t(y * code->paddedSide + x)], range.mean);
      }
    }
  }
}

TEST(FractalCodec, ResidualLayerBoundsEverySample) {
  TELLUS_REQUIRE_SHARED_DATA(data);
  const TileShape shape{257, 257};
  for (int origin : {600, 900}) {
    const Tile tile = realTile(data, 257, origin);
    for (std::uint32_t bound : {0u, 1u, 3u}) {
      CodecOptions options{.maxErrorSteps = bound, .zstdLevel = 3};
      options.fractal.residual = true;
      auto codec = makeCodec("fractal", options);
      ASSERT_TRUE(codec);
      EXPECT_TRUE(codec.value()->boundsError());
      std::vector<std::byte> bytes;
      ASSERT_TRUE(codec.value()->encode(tile, shape, bytes));
      Tile decoded(tile.size());
      ASSERT_TRUE(codec.value()->decode(bytes, shape, decoded));
      EXPECT_LE(maxAbs(decoded, tile), std::int64_t(bound)) << "bound " << bound;
      if (bound > 0) {
        EXPECT_EQ(maxAbs(decoded, tile), std::int64_t(bound));
      }
    }
  }
}

TEST(FractalCodec, WithoutResidualTheCodecBoundsNothingButDecodesWhatWasEncoded) {
  TELLUS_REQUIRE_SHARED_DATA(data);
  const TileShape shape{65, 65};
  const Tile tile = realTile(data, 65, 850);
  auto codec = makeCodec("fractal", {.maxErrorSteps = 0, .zstdLevel = 3});
  ASSERT_TRUE(codec);
  EXPECT_FALSE(codec.value()->boundsError());
  EXPECT_FALSE(codec.value()->lossless());
  std::vector<std::byte> bytes;
  ASSERT_TRUE(codec.value()->encode(tile, shape, bytes));
  const auto code = fractal::read(bytes, shape);
  ASSERT_TRUE(code) << code.error().message;
  Tile decoded(tile.size());
  ASSERT_TRUE(codec.value()->decode(bytes, shape, decoded));
  EXPECT_EQ(decoded, decodeAfter(code.value(), code->iterations));
  EXPECT_LT(bytes.size(), tile.size() * 2);  // well under 16 bits per sample
}

// Tiles of a store share their border samples with their neighbours. The exact border makes
// both decode them to the source values after any number of iterations, so they agree.
TEST(FractalCodec, TheBorderDecodesExactlySoNeighbouringTilesAgree) {
  TELLUS_REQUIRE_SHARED_DATA(data);
  const TileShape shape{65, 65};
  const Tile source = realTile(data, 129, 850);  // two tiles side by side share column 64
  auto tileAt = [&](int x0) {
    Tile tile(shape.sampleCount());
    for (int y = 0; y < 65; ++y) {
      for (int x = 0; x < 65; ++x)
        tile[std::size_t(y * 65 + x)] = source[std::size_t(y * 129 + x0 + x)];
    }
    return tile;
  };
  auto columnOf = [](const Tile& tile, int x) {
    Tile column;
    for (int y = 0; y < 65; ++y) column.push_back(tile[std::size_t(y * 65 + x)]);
    return column;
  };
  const Tile west = tileAt(0), east = tileAt(64);
  const auto westCode = fractal::encode(west, shape, {}, 0);
  const auto eastCode = fractal::encode(east, shape, {}, 0);
  ASSERT_TRUE(westCode && eastCode);
  ASSERT_EQ(westCode->border.size(), std::size_t(fractal::borderLength(shape)));
  // The border survives the payload.
  std::vector<std::byte> bytes;
  ASSERT_TRUE(fractal::write(westCode.value(), 2, 2, 0, 3, bytes));
  const auto read = fractal::read(bytes, shape);
  ASSERT_TRUE(read) << read.error().message;
  EXPECT_EQ(read->border, westCode->border);
  for (int iterations : {1, 2, westCode->iterations}) {
    const Tile w = decodeAfter(read.value(), iterations),
               e = decodeAfter(eastCode.value(), iterations);
    EXPECT_EQ(columnOf(w, 64), columnOf(west, 64)) << iterations << " iterations";
    EXPECT_EQ(columnOf(w, 64), columnOf(e, 0)) << iterations << " iterations";
    EXPECT_EQ(columnOf(w, 0), columnOf(west, 0));
    EXPECT_GT(maxAbs(w, west), 0);  // the interior stays approximate
  }
  // Without the exact border the shared column decodes differently in the two tiles.
  FractalOptions borderless;
  borderless.exactBorder = false;
  const auto westPlain = fractal::encode(west, shape, borderless, 0);
  const auto eastPlain = fractal::encode(east, shape, borderless, 0);
  ASSERT_TRUE(westPlain && eastPlain);
  EXPECT_TRUE(westPlain->border.empty());
  EXPECT_NE(columnOf(decodeAfter(westPlain.value(), westPlain->iterations), 64),
            columnOf(decodeAfter(eastPlain.value(), eastPlain->iterations), 0));
  // What the border costs: under 1.5 bytes per border sample.
  std::vector<std::byte> plainBytes;
  ASSERT_TRUE(fractal::write(westPlain.value(), 2, 2, 0, 3, plainBytes));
  EXPECT_LT(double(bytes.size() - plainBytes.size()), 1.5 * double(westCode->border.size()));
}

TEST(FractalCodec, NearestNeighbourSearchMatchesTheFullScan) {
  TELLUS_REQUIRE_SHARED_DATA(data);
  const TileShape shape{65, 65};
  const Tile tile = realTile(data, 65, 700);
  FractalOptions fast, full;
  full.fullSearch = true;
  const auto a = fractal::encode(tile, shape, fast, 0);
  const auto b = fractal::encode(tile, shape, full, 0);
  ASSERT_TRUE(a && b);
  const double fastError = rmse(decodeAfter(a.value(), 8), tile);
  const double fullError = rmse(decodeAfter(b.value(), 8), tile);
  EXPECT_LE(fullError, fastError * 1.001);
  EXPECT_LE(fastError, fullError * 1.15) << "the k-d tree search misses good domains";
}

TEST(FractalCodec, QuadtreeSplitsRangesThatFitPoorly) {
  TELLUS_REQUIRE_SHARED_DATA(data);
  const TileShape shape{129, 129};
  const Tile tile = realTile(data, 129, 700);
  FractalOptions fixed, tree;
  fixed.rangeSize = 2;
  tree.rangeSize = 2;
  tree.quadtreeLevels = 3;  // 8x8 ranges split down to 2x2
  tree.splitRmseSteps = 12.0;
  const auto a = fractal::encode(tile, shape, fixed, 0);
  const auto b = fractal::encode(tile, shape, tree, 0);
  ASSERT_TRUE(a && b);
  int sizes[5] = {};
  for (const auto& range : b->ranges) ++sizes[range.sizeLog2];
  EXPECT_GT(sizes[1], 0);
  EXPECT_GT(sizes[2], 0);
  EXPECT_GT(sizes[3], 0);
  EXPECT_LT(b->ranges.size(), a->ranges.size());
  EXPECT_LT(rmse(decodeAfter(b.value(), 8), tile), 12.0);
  // Round trip through bytes keeps the tree.
  std::vector<std::byte> bytes;
  ASSERT_TRUE(fractal::write(b.value(), 1, 3, 0, 3, bytes));
  const auto back = fractal::read(bytes, shape);
  ASSERT_TRUE(back) << back.error().message;
  EXPECT_EQ(back->ranges.size(), b->ranges.size());
  EXPECT_EQ(decodeAfter(back.value(), 6), decodeAfter(b.value(), 6));
}

TEST(FractalCodec, RefusesBadOptionsAndHugeRelief) {
  for (auto change :
       {+[](FractalOptions& o) { o.rangeSize = 3; }, +[](FractalOptions& o) { o.rangeSize = 32; },
        +[](FractalOptions& o) { o.quadtreeLevels = 0; },
        +[](FractalOptions& o) { o.quadtreeLevels = 4; },  // 4 << 3 > 16
        +[](FractalOptions& o) { o.domainStep = 3; }, +[](FractalOptions& o) { o.candidates = 0; },
        +[](FractalOptions& o) { o.iterations = 99; }}) {
    CodecOptions options;
    change(options.fractal);
    EXPECT_FALSE(makeCodec("fractal", options));
  }
  Tile cliff(17 * 17, 0);
  cliff[5] = 2'000'000;
  const auto code = fractal::encode(cliff, {17, 17}, {}, 0);
  ASSERT_FALSE(code);
  EXPECT_NE(code.error().message.find("relief"), std::string::npos);
}

TEST(FractalCodec, ReaderRefusesCorruptCodes) {
  TELLUS_REQUIRE_SHARED_DATA(data);
  const TileShape shape{33, 33};
  const Tile tile = realTile(data, 33, 880);
  const auto code = fractal::encode(tile, shape, {}, 0);
  ASSERT_TRUE(code);
  std::vector<std::byte> bytes;
  ASSERT_TRUE(fractal::write(code.value(), 2, 2, 0, 3, bytes));
  ASSERT_TRUE(fractal::read(bytes, shape));
  EXPECT_FALSE(fractal::read(bytes, {65, 65}));  // padded side too small for the shape
  for (std::size_t at : {std::size_t(0), std::size_t(3), std::size_t(6)}) {
    std::vector<std::byte> bad = bytes;
    bad[at] = std::byte(0x7f);
    EXPECT_FALSE(fractal::read(bad, shape)) << "byte " << at;
  }
  std::vector<std::byte> noBorderFlag = bytes;  // the border stream becomes trailing bytes
  noBorderFlag[1] = std::byte(0);
  EXPECT_FALSE(fractal::read(noBorderFlag, shape));
  std::vector<std::byte> longer = bytes;
  longer.push_back(std::byte(0));
  EXPECT_FALSE(fractal::read(longer, shape));
}

}  // namespace
}  // namespace tellus
