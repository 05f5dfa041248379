#pragma once
// A regular grid of heights with its georeferencing, and its place in the world frame.
//
// World frame (used everywhere in Tellus): x east, y north, z up, in metres; the origin is
// the south-west sample of the grid. Sample (col, row) — row 0 is the northern edge — sits at
// x = col * spacingXM, y = (height - 1 - row) * spacingYM, z = its height.
#include <array>
#include <cstddef>
#include <string>
#include <vector>

#include "tellus/core/aabb.hpp"

namespace tellus {

struct GeoReference {
  std::string crsWkt;   // WKT of the CRS; empty when the input had none
  std::string crsName;  // short human-readable name ("WGS 84", "WGS 84 / UTM zone 33N")
  bool hasGeoTransform = false;
  // GDAL geotransform: Xgeo = gt[0] + col*gt[1] + row*gt[2]; Ygeo = gt[3] + col*gt[4] + row*gt[5]
  // (col, row at the pixel's top-left corner for pixel-is-area rasters).
  std::array<double, 6> geoTransform{0.0, 1.0, 0.0, 0.0, 0.0, -1.0};
  bool isGeographic = false;  // CRS in degrees (lon/lat)
};

// Largest raster side Tellus accepts, in samples (2^24 + 1: 500 km at 3 cm, the planet at
// 2.4 m); the tile pyramid has the same limit.
inline constexpr int kMaxGridSide = (1 << 24) + 1;

struct HeightRange {
  float minM = 0.0f;
  float maxM = 0.0f;
};

struct HeightGrid {
  int width = 0;
  int height = 0;
  std::vector<float> heights;  // metres, row-major, row 0 = north; width * height values
  double spacingXM = 1.0;      // ground distance between horizontal neighbours (east-west), metres
  double spacingYM = 1.0;      // ground distance between vertical neighbours (north-south), metres
  GeoReference georef;
  std::size_t filledVoidCount = 0;  // void samples in the input, filled by interpolation

  HeightGrid() = default;
  HeightGrid(int w, int h) : width(w), height(h), heights(std::size_t(w) * std::size_t(h), 0.0f) {}

  float at(int col, int row) const {
    return heights[std::size_t(row) * std::size_t(width) + std::size_t(col)];
  }
  float& at(int col, int row) {
    return heights[std::size_t(row) * std::size_t(width) + std::size_t(col)];
  }

  HeightRange heightRange() const;  // O(width * height)

  // Box around the whole terrain in the world frame (heights from heightRange()).
  Aabb worldBounds() const;

  // Height at world (x, y) by bilinear interpolation, clamped to the grid's edges. Metres.
  float heightAtWorld(double x, double y) const;
  // Height at world (x, y) of the full-resolution triangle mesh, clamped to the grid's edges:
  // each cell split along the diagonal from its north-east to its south-west sample, as the
  // reference renderer draws it. The ground truth of the screen-space error. Metres.
  double meshHeightAtWorld(double x, double y) const;
};

}  // namespace tellus
