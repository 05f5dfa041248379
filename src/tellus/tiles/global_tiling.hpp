#pragma once
// The tiling scheme of a global store: a latitude/longitude quadtree on WGS84 geodetic
// coordinates (the geographic tiling of Cesium's and TMS's "geodetic" profile).
//
// Depth 0 has two root tiles of 180 x 180 degrees, x = 0 west of Greenwich (-180..0) and x = 1
// east of it (0..180); every tile has four children, so depth d has 2^(d+1) x 2^d tiles of
// 180 / 2^d degrees. y = 0 is the northern row (90 N down), as row 0 of a HeightGrid is north.
// Deeper is finer: the opposite of the flat pyramid's levels (pyramid_layout.hpp), hence the
// different name.
//
// A tile holds (cells + 1)^2 samples on a regular lat/lon grid that includes its four edges, so
// neighbours share their edge samples exactly: across the antimeridian (lon 180 = lon -180) the
// last tile's eastern column is the first tile's western column, and across a pole a tile's
// northern (southern) row touches the tile half way round the globe, rotated by 180 degrees.
//
// Poles: a tile's northern row in the top tile row (y = 0) lies on the north pole, every sample
// of it the same point on the ellipsoid; the builder gives every such sample one value (the
// sources' height at the pole), so the pole is one point, not a fan of spikes. Likewise south.
#include <compare>
#include <vector>

#include "tellus/core/result.hpp"

namespace tellus {

struct GeoTileKey {
  int depth = 0;
  int x = 0;  // 0 .. 2^(depth + 1) - 1, west to east from -180
  int y = 0;  // 0 .. 2^depth - 1, north to south from 90
  auto operator<=>(const GeoTileKey&) const = default;
};

// A box in degrees; west < east except for a box across the antimeridian, which this scheme's
// functions never return (they split it).
struct GeoBounds {
  double westDeg = 0.0, southDeg = 0.0, eastDeg = 0.0, northDeg = 0.0;
};

enum class GeoSide { North, East, South, West };

struct GeoNeighbour {
  GeoTileKey key;
  // The neighbour lies across a pole: its rows and columns run the other way (rotated 180
  // degrees), so its northern row meets this tile's northern row, east to west.
  bool acrossPole = false;
};

class GlobalTiling {
 public:
  // The deepest depth accepted (2^30 columns still fit an int): tiles of 180 / 2^29 degrees,
  // 3.7 cm on the equator.
  static constexpr int kMaxDepth = 29;

  static int tilesX(int depth) { return 2 << depth; }
  static int tilesY(int depth) { return 1 << depth; }
  static double tileSizeDeg(int depth) { return 180.0 / double(1 << depth); }
  static bool contains(GeoTileKey key);

  static GeoBounds bounds(GeoTileKey key);
  // The tile of `depth` that holds (lat, lon): longitudes wrap; a point on a tile edge belongs
  // to the tile east and south of it, except at 180 E and 90 S (the last tile).
  static GeoTileKey tileAt(int depth, double latDeg, double lonDeg);
  // Latitude and longitude of sample (column i, row j) of a tile of `cells` cells a side.
  static double sampleLatDeg(GeoTileKey key, int cells, int row);
  static double sampleLonDeg(GeoTileKey key, int cells, int column);

  static GeoTileKey parent(GeoTileKey key);  // depth 0's parent is itself
  static std::vector<GeoTileKey> children(GeoTileKey key);  // NW, NE, SW, SE
  static GeoNeighbour neighbour(GeoTileKey key, GeoSide side);
  // Every tile of `depth` that intersects `box` (a box across the antimeridian may be given with
  // east < west). Errors on an absurd count (> maxTiles).
  static Result<std::vector<GeoTileKey>> tilesCovering(int depth, const GeoBounds& box,
                                                       std::size_t maxTiles = 1'000'000);
};

}  // namespace tellus
