#pragma once
// SRTM-like tiles of the procedural planet (issue 47's planet-scale input data): one-degree
// tiles of 1201 x 1201 big-endian Int16 samples (3 arc-seconds, the edges shared with the
// neighbours, row 0 north), named and laid out as SRTM3 .hgt files (N37E127.hgt: 37..38 N,
// 127..128 E), voids (-32768) in clusters on steep ground as SRTM has them, the sea at 0 m and
// tiles of open sea left out, as SRTM does. Deterministic per seed; samples from PlanetField
// with relief down to about 50 m (planet_generator.hpp). GL-free.
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "tellus/core/result.hpp"
#include "tellus/dem/planet_generator.hpp"

namespace tellus {

inline constexpr int kSrtmTileSamples = 1201;
inline constexpr std::int16_t kSrtmVoid = -32768;

// A tile by its south-west corner (whole degrees).
struct SrtmTileId {
  int south = 0, west = 0;
  bool operator==(const SrtmTileId&) const = default;
};
// "N37E127.hgt", "S05W071.hgt".
std::string srtmTileName(const SrtmTileId& tile);

// Whole degrees, west < east, south < north, within -180..180 and -90..90.
struct LatLonDegreeBox {
  int west = 0, south = 0, east = 0, north = 0;
};

struct SrtmTileOptions {
  PlanetParams planet;  // columns unused: the tiles sample the field directly
  int detailOctaves = 10;  // PlanetField's detail below the planet's own relief
};

// The tiles of `box` with land on them (the continents' shape probed every 0.05 degrees over
// each tile and its edges), in row-major order from the north-west; SRTM has no tile of open
// sea. Land narrower than the probe spacing can be missed.
std::vector<SrtmTileId> srtmLandTiles(const PlanetField& field, const LatLonDegreeBox& box);

// A tile's samples, row 0 north: metres rounded, the sea 0, voids kSrtmVoid. A tile's edge rows
// and columns equal its neighbours' (the same points of the same field).
std::vector<std::int16_t> srtmTileSamples(const PlanetField& field, const SrtmTileId& tile, int detailOctaves);

// Writes `samples` as a .hgt file (big-endian), atomically.
Status writeSrtmTile(const std::filesystem::path& path, const std::vector<std::int16_t>& samples);

}  // namespace tellus
