#include "tellus/dem/srtm_tile_generator.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>
#include <tbb/parallel_for.h>

#include "tellus/core/atomic_output.hpp"

namespace tellus {
namespace {

// A cheap, deterministic hash of a sample's integer position (voids are decided per 3x3 cell
// block so that they come in clusters).
std::uint64_t mix(std::uint64_t x) {
  x ^= x >> 33;
  x *= 0xff51afd7ed558ccdULL;
  x ^= x >> 33;
  x *= 0xc4ceb9fe1a85ec53ULL;
  x ^= x >> 33;
  return x;
}

}  // namespace

std::string srtmTileName(const SrtmTileId& tile) {
  return fmt::format("{}{:02d}{}{:03d}.hgt", tile.south >= 0 ? 'N' : 'S', std::abs(tile.south),
                     tile.west >= 0 ? 'E' : 'W', std::abs(tile.west));
}

std::vector<SrtmTileId> srtmLandTiles(const PlanetField& field, const LatLonDegreeBox& box) {
  // A row of tiles a task, the rows joined north to south.
  std::vector<std::vector<SrtmTileId>> rows(std::size_t(box.north - box.south));
  tbb::parallel_for(0, box.north - box.south, [&](int r) {
    const int south = box.north - 1 - r;
    for (int west = box.west; west < box.east; ++west) {
      bool land = false;
      constexpr int kProbes = 20;  // every 0.05 degrees, edges included
      for (int j = 0; j <= kProbes && !land; ++j) {
        for (int i = 0; i <= kProbes && !land; ++i) {
          land = field.landness(south + double(j) / kProbes, west + double(i) / kProbes) > 0.0;
        }
      }
      if (land) rows[std::size_t(r)].push_back({south, west});
    }
  });
  std::vector<SrtmTileId> tiles;
  for (const std::vector<SrtmTileId>& row : rows) tiles.insert(tiles.end(), row.begin(), row.end());
  return tiles;
}

std::vector<std::int16_t> srtmTileSamples(const PlanetField& field, const SrtmTileId& tile, int detailOctaves) {
  constexpr int n = kSrtmTileSamples;
  std::vector<std::int16_t> samples(std::size_t(n) * n);
  tbb::parallel_for(0, n, [&](int row) {
    // Sample positions from whole arc-seconds (exact in every tile), so shared edges agree.
    const int latArcSec = (tile.south + 1) * 3600 - row * 3;
    const double latDeg = latArcSec / 3600.0;
    for (int col = 0; col < n; ++col) {
      const int lonArcSec = tile.west * 3600 + col * 3;
      const double lonDeg = lonArcSec / 3600.0;
      bool land = false;
      const double h = field.heightM(latDeg, lonDeg, detailOctaves, &land);
      std::int16_t value = land ? std::int16_t(std::clamp(std::lround(h), -500L, 8800L)) : std::int16_t(0);
      // Voids: SRTM's radar lost steep slopes and shadows. Here, on high ground, one 3x3-sample
      // block in about 60 above 2,000 m, whole blocks at a time, by a hash of the block's
      // position on the globe (the same in both tiles of a shared edge).
      if (land && h > 2000.0) {
        const std::uint64_t block =
            (std::uint64_t(std::int64_t(latArcSec / 9) + (1 << 20)) << 32) ^ std::uint64_t(std::int64_t(lonArcSec / 9) + (1 << 22));
        if (mix(block ^ 0x9e3779b97f4a7c15ULL) % 60 == 0) value = kSrtmVoid;
      }
      samples[std::size_t(row) * n + std::size_t(col)] = value;
    }
  });
  return samples;
}

Status writeSrtmTile(const std::filesystem::path& path, const std::vector<std::int16_t>& samples) {
  std::vector<std::byte> bytes(samples.size() * 2);
  for (std::size_t k = 0; k < samples.size(); ++k) {
    const auto v = std::uint16_t(samples[k]);
    bytes[2 * k] = std::byte(v >> 8);  // big-endian, as SRTM
    bytes[2 * k + 1] = std::byte(v & 0xff);
  }
  return writeFileAtomically(path, [&](const std::filesystem::path& temp) {
    return writeBytesChecked(temp, bytes, path.string());
  });
}

}  // namespace tellus
