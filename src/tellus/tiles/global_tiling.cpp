#include "tellus/tiles/global_tiling.hpp"

#include <algorithm>
#include <cmath>

namespace tellus {

bool GlobalTiling::contains(GeoTileKey key) {
  return key.depth >= 0 && key.depth <= kMaxDepth && key.x >= 0 && key.x < tilesX(key.depth) &&
         key.y >= 0 && key.y < tilesY(key.depth);
}

GeoBounds GlobalTiling::bounds(GeoTileKey key) {
  const double size = tileSizeDeg(key.depth);
  GeoBounds b;
  b.westDeg = -180.0 + key.x * size;
  b.eastDeg = b.westDeg + size;
  b.northDeg = 90.0 - key.y * size;
  b.southDeg = b.northDeg - size;
  return b;
}

GeoTileKey GlobalTiling::tileAt(int depth, double latDeg, double lonDeg) {
  const double size = tileSizeDeg(depth);
  double lon = std::fmod(lonDeg + 180.0, 360.0);
  if (lon < 0.0) lon += 360.0;
  if (lonDeg == 180.0) lon = 360.0;  // 180 E itself: the last tile, not the first
  const double lat = std::clamp(latDeg, -90.0, 90.0);
  GeoTileKey key;
  key.depth = depth;
  key.x = std::clamp(int(std::floor(lon / size)), 0, tilesX(depth) - 1);
  key.y = std::clamp(int(std::floor((90.0 - lat) / size)), 0, tilesY(depth) - 1);
  return key;
}

double GlobalTiling::sampleLatDeg(GeoTileKey key, int cells, int row) {
  const GeoBounds b = bounds(key);
  // Edges exactly (no rounding): shared rows of neighbours are bit-identical.
  if (row == 0) return b.northDeg;
  if (row == cells) return b.southDeg;
  return b.northDeg - (b.northDeg - b.southDeg) * double(row) / double(cells);
}

double GlobalTiling::sampleLonDeg(GeoTileKey key, int cells, int column) {
  const GeoBounds b = bounds(key);
  if (column == 0) return b.westDeg;
  if (column == cells) return b.eastDeg;
  return b.westDeg + (b.eastDeg - b.westDeg) * double(column) / double(cells);
}

GeoTileKey GlobalTiling::parent(GeoTileKey key) {
  if (key.depth == 0) return key;
  return {key.depth - 1, key.x / 2, key.y / 2};
}

std::vector<GeoTileKey> GlobalTiling::children(GeoTileKey key) {
  const int d = key.depth + 1, x = key.x * 2, y = key.y * 2;
  return {{d, x, y}, {d, x + 1, y}, {d, x, y + 1}, {d, x + 1, y + 1}};
}

GeoNeighbour GlobalTiling::neighbour(GeoTileKey key, GeoSide side) {
  const int nx = tilesX(key.depth), ny = tilesY(key.depth);
  const int opposite = (key.x + nx / 2) % nx;  // half way round the globe
  switch (side) {
    case GeoSide::East:
      return {{key.depth, (key.x + 1) % nx, key.y}, false};
    case GeoSide::West:
      return {{key.depth, (key.x + nx - 1) % nx, key.y}, false};
    case GeoSide::North:
      if (key.y == 0) return {{key.depth, opposite, 0}, true};
      return {{key.depth, key.x, key.y - 1}, false};
    case GeoSide::South:
      if (key.y == ny - 1) return {{key.depth, opposite, ny - 1}, true};
      return {{key.depth, key.x, key.y + 1}, false};
  }
  return {key, false};
}

Result<std::vector<GeoTileKey>> GlobalTiling::tilesCovering(int depth, const GeoBounds& box,
                                                            std::size_t maxTiles) {
  if (depth < 0 || depth > kMaxDepth) {
    return makeError("depth {} is outside 0..{}", depth, kMaxDepth);
  }
  if (!(box.southDeg <= box.northDeg) || !std::isfinite(box.westDeg) ||
      !std::isfinite(box.eastDeg) || !std::isfinite(box.southDeg) ||
      !std::isfinite(box.northDeg)) {
    return makeError("bounds ({}, {}, {}, {}) are not a box", box.westDeg, box.southDeg,
                     box.eastDeg, box.northDeg);
  }
  // Tiles that share area with the box (a box edge on a tile edge does not take the tile
  // beyond it); a box across the antimeridian wraps its columns.
  const double size = tileSizeDeg(depth);
  const int nx = tilesX(depth), ny = tilesY(depth);
  const auto firstIndex = [size](double offset) { return int(std::floor(offset / size)); };
  const auto lastIndex = [size](double offset) { return int(std::ceil(offset / size)) - 1; };
  const double north = std::min(box.northDeg, 90.0), south = std::max(box.southDeg, -90.0);
  const int y0 = std::clamp(firstIndex(90.0 - north), 0, ny - 1);
  const int y1 = std::clamp(std::max(y0, lastIndex(90.0 - south)), y0, ny - 1);
  const bool wholeWidth = box.eastDeg - box.westDeg >= 360.0;
  int x0 = 0, x1 = nx - 1;
  if (!wholeWidth) {
    double west = std::fmod(box.westDeg + 180.0, 360.0);
    if (west < 0.0) west += 360.0;
    double east = west + std::fmod(box.eastDeg - box.westDeg + 360.0, 360.0);
    x0 = firstIndex(west);
    x1 = std::max(x0, lastIndex(east));  // may pass nx: wraps below
  }
  const int columns = std::min(x1 - x0 + 1, nx);
  const std::size_t count = std::size_t(columns) * std::size_t(y1 - y0 + 1);
  if (count > maxTiles) {
    return makeError("{} tiles at depth {} cover the box, more than {}", count, depth, maxTiles);
  }
  std::vector<GeoTileKey> tiles;
  tiles.reserve(count);
  for (int y = y0; y <= y1; ++y) {
    for (int i = 0; i < columns; ++i) tiles.push_back({depth, (x0 + i) % nx, y});
  }
  return tiles;
}

}  // namespace tellus
