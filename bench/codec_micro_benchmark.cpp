// Google Benchmark micro-benchmarks: encode and decode of one 257x257 tile per codec, on a tile
// of real SRTM data (N36E137, Japan Alps) when ../shared/data is present, else on procedural
// terrain. Run: build/release/bench/tellus_micro_benchmarks
#include <benchmark/benchmark.h>

#include <filesystem>

#include "tellus/dem/dem_loader.hpp"
#include "tellus/dem/terrain_generator.hpp"
#include "tellus/eval/codec_benchmark.hpp"

namespace tellus {
namespace {

constexpr int kTileCells = 256;

const QuantisedTiles& benchmarkTile() {
  static const QuantisedTiles tiles = [] {
    const std::filesystem::path hgt =
        std::filesystem::path(TELLUS_SHARED_DATA_DIR) / "srtm3-hgt-east-asia/N36E137.hgt";
    Result<HeightGrid> grid =
        std::filesystem::exists(hgt) ? loadDem({hgt}) : Result<HeightGrid>(Error{});
    if (!grid) {
      TerrainParams params;
      params.size = kTileCells + 1;
      grid = generateTerrain(params);
    }
    HeightGrid g = std::move(grid.value());
    // One tile from the middle of the grid.
    HeightGrid tile(kTileCells + 1, kTileCells + 1);
    const int x0 = (g.width - kTileCells - 1) / 2, y0 = (g.height - kTileCells - 1) / 2;
    for (int j = 0; j <= kTileCells; ++j)
      for (int i = 0; i <= kTileCells; ++i) tile.at(i, j) = g.at(x0 + i, y0 + j);
    return cutTiles(tile, kTileCells, 1.0);
  }();
  return tiles;
}

void encodeTile(benchmark::State& state, const std::string& name, std::uint32_t bound) {
  const QuantisedTiles& tiles = benchmarkTile();
  auto codec = makeCodec(name, {.maxErrorSteps = bound, .zstdLevel = 12});
  std::vector<std::byte> out;
  for (auto _ : state) {
    out.clear();
    benchmark::DoNotOptimize(codec.value()->encode(tiles.tiles[0], tiles.shape, out));
  }
  state.SetItemsProcessed(state.iterations() * std::int64_t(tiles.shape.sampleCount()));
  state.counters["bytes"] = double(out.size());
}

void decodeTile(benchmark::State& state, const std::string& name, std::uint32_t bound) {
  const QuantisedTiles& tiles = benchmarkTile();
  auto codec = makeCodec(name, {.maxErrorSteps = bound, .zstdLevel = 12});
  std::vector<std::byte> encoded;
  (void)codec.value()->encode(tiles.tiles[0], tiles.shape, encoded);
  std::vector<std::int32_t> samples(tiles.shape.sampleCount());
  for (auto _ : state) {
    benchmark::DoNotOptimize(codec.value()->decode(encoded, tiles.shape, samples));
  }
  state.SetItemsProcessed(state.iterations() * std::int64_t(tiles.shape.sampleCount()));
}

BENCHMARK_CAPTURE(encodeTile, raw, "raw", 0);
BENCHMARK_CAPTURE(encodeTile, zstd, "zstd", 0);
BENCHMARK_CAPTURE(encodeTile, bounded_1m, "bounded", 1);
BENCHMARK_CAPTURE(encodeTile, lerc_1m, "lerc", 1);
BENCHMARK_CAPTURE(decodeTile, raw, "raw", 0);
BENCHMARK_CAPTURE(decodeTile, zstd, "zstd", 0);
BENCHMARK_CAPTURE(decodeTile, bounded_1m, "bounded", 1);
BENCHMARK_CAPTURE(decodeTile, lerc_1m, "lerc", 1);

}  // namespace
}  // namespace tellus

BENCHMARK_MAIN();
