#include "tellus/eval/codec_benchmark.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>

#include <tbb/parallel_for.h>

namespace tellus {
namespace {

double median(std::vector<double> values) {
  std::sort(values.begin(), values.end());
  return values[values.size() / 2];
}

template <typename F>
double secondsOf(F&& f) {
  const auto start = std::chrono::steady_clock::now();
  f();
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace

QuantisedTiles cutTiles(const HeightGrid& grid, int tileSize, double quantumM) {
  QuantisedTiles out;
  const int n = tileSize;
  out.shape = {n + 1, n + 1};
  out.tilesX = (grid.width - 2) / n + 1;
  out.tilesY = (grid.height - 2) / n + 1;
  for (int ty = 0; ty < out.tilesY; ++ty) {
    for (int tx = 0; tx < out.tilesX; ++tx) {
      std::vector<std::int32_t> tile(out.shape.sampleCount());
      for (int j = 0; j <= n; ++j) {
        const int row = std::min(ty * n + j, grid.height - 1);
        for (int i = 0; i <= n; ++i) {
          const int col = std::min(tx * n + i, grid.width - 1);
          tile[std::size_t(j) * std::size_t(n + 1) + std::size_t(i)] =
              std::int32_t(std::nearbyint(double(grid.at(col, row)) / quantumM));
        }
      }
      out.tiles.push_back(std::move(tile));
    }
  }
  return out;
}

void compareHeights(const std::vector<float>& a, const std::vector<float>& b, double& maxAbs,
                    double& rmse) {
  double sum = 0.0;
  maxAbs = 0.0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    const double d = double(a[i]) - double(b[i]);
    maxAbs = std::max(maxAbs, std::abs(d));
    sum += d * d;
  }
  rmse = std::sqrt(sum / double(std::max<std::size_t>(a.size(), 1)));
}

Result<CodecMeasurement> measureCodec(const TileCodec& codec, const QuantisedTiles& tiles,
                                      const HeightGrid& grid, double quantumM, int repeats) {
  std::vector<std::vector<std::byte>> encoded(tiles.tiles.size());
  std::vector<std::vector<std::int32_t>> decoded(
      tiles.tiles.size(), std::vector<std::int32_t>(tiles.shape.sampleCount()));
  std::vector<double> encodeTimes, encodeAllCoresTimes, decodeTimes;
  Status status;
  for (int r = 0; r < std::max(1, repeats); ++r) {
    encodeTimes.push_back(secondsOf([&] {
      for (std::size_t t = 0; t < tiles.tiles.size() && status; ++t) {
        encoded[t].clear();
        status = codec.encode(tiles.tiles[t], tiles.shape, encoded[t]);
      }
    }));
    std::vector<Status> failures(tiles.tiles.size());
    encodeAllCoresTimes.push_back(secondsOf([&] {
      tbb::parallel_for(std::size_t(0), tiles.tiles.size(), [&](std::size_t t) {
        std::vector<std::byte> bytes;
        failures[t] = codec.encode(tiles.tiles[t], tiles.shape, bytes);
      });
    }));
    for (const Status& s : failures) {
      if (!s) status = s;
    }
    decodeTimes.push_back(secondsOf([&] {
      for (std::size_t t = 0; t < tiles.tiles.size() && status; ++t) {
        status = codec.decode(encoded[t], tiles.shape, decoded[t]);
      }
    }));
    if (!status) return makeError("{}: {}", codec.name(), status.error().message);
  }
  CodecMeasurement m;
  for (const auto& e : encoded) m.bytes += e.size();
  m.payloads = std::move(encoded);
  m.encodeSeconds = median(encodeTimes);
  m.encodeSecondsAllCores = median(encodeAllCoresTimes);
  m.decodeSeconds = median(decodeTimes);
  compareHeights(assembleTiles(decoded, tiles, grid, quantumM), grid.heights, m.maxAbsErrorM,
                 m.rmseM);
  return m;
}

std::vector<float> assembleTiles(const std::vector<std::vector<std::int32_t>>& decoded,
                                 const QuantisedTiles& tiles, const HeightGrid& grid,
                                 double quantumM) {
  std::vector<float> heights(grid.heights.size());
  const int n = tiles.shape.width - 1;
  for (int ty = 0; ty < tiles.tilesY; ++ty) {
    for (int tx = 0; tx < tiles.tilesX; ++tx) {
      const auto& tile = decoded[std::size_t(ty * tiles.tilesX + tx)];
      for (int j = 0; j <= n && ty * n + j < grid.height; ++j) {
        for (int i = 0; i <= n && tx * n + i < grid.width; ++i) {
          heights[std::size_t(ty * n + j) * std::size_t(grid.width) + std::size_t(tx * n + i)] =
              float(tile[std::size_t(j) * std::size_t(n + 1) + std::size_t(i)] * quantumM);
        }
      }
    }
  }
  return heights;
}

}  // namespace tellus
