#pragma once
// One quantized-mesh-1.0 tile of the geographic tiling scheme (2 x 1 tiles at level 0, y from
// the south), built so that the surface a client draws is within a bound of the data in 3-D:
//
// - What is measured: the distance between a true surface point (a source sample at its
//   longitude, latitude and height, converted to ECEF; or, where the source has no data, the
//   ellipsoid or the geoid at a lattice point) and the point of the flat triangle the client
//   draws between its corners' ECEF positions, at the same tile coordinates. That is how far
//   the drawn chord lies from the curved, real surface: Earth's curvature included (a level-0
//   tile's flat triangles between border vertices lie thousands of kilometres inside the
//   planet), and the data's every sample, not a resampled lattice.
// - Edges: each tile edge is sampled at the source's spacing (at most 32,768 points, at
//   quantized positions) and simplified in 3-D (Douglas-Peucker, within the same bound); both
//   tiles sharing an edge compute it from the same inputs, so they get the same vertices.
// - Interior: greedy insertion into a Delaunay triangulation over the source samples inside
//   the tile and the lattice points where there is no data (greedy_tin.hpp), until every one
//   is within the bound.
// - Normals: the data's, from central differences one source spacing (or 1/256 of the tile)
//   apart; a shared edge vertex gets the same normal in both tiles.
// GL-free; GDAL/PROJ only through LonLatSampler.
#include <array>
#include <cstdint>
#include <vector>

#include <glm/vec3.hpp>

#include "tellus/core/result.hpp"
#include "tellus/dem/geoid.hpp"
#include "tellus/dem/water_mask.hpp"
#include "tellus/export/lonlat_sampler.hpp"
#include "tellus/export/quantized_mesh.hpp"

namespace tellus {

struct QuantizedMeshTileAddress {
  int level = 0, x = 0, y = 0;  // the geographic scheme's, y from the south
};

struct QuantizedMeshTileOptions {
  double maxErrorM = 1.0;           // the 3-D bound, metres
  int latticeSamples = 65;          // the lattice (a side) standing in for missing data
  std::uint64_t maxTruthSamples = std::uint64_t(1) << 22;  // source samples a tile measures at most
  const Geoid* geoid = nullptr;     // orthometric -> ellipsoidal heights when set
  // Where the source has no data, the ground is this coarser model's (heights above the geoid,
  // sea floors taken as the sea surface: a global relief such as ETOPO5), else the geoid.
  const LonLatSampler* background = nullptr;
  // The data's box: an edge that misses it is sampled on the lattice (no data to follow),
  // one that meets it at the source's spacing. Empty (the default): every edge at the
  // source's spacing.
  LonLatBox dataBounds{0.0, 0.0, -1.0, -1.0};
  // The bound each edge is simplified within (west, east, south, north), metres; 0: maxErrorM.
  // Two tiles sharing an edge must give it the same bound to get the same vertices on it.
  std::array<double, 4> edgeErrorM{0.0, 0.0, 0.0, 0.0};
  // When set, the tile gets the watermask extension: the mask's nearest pixel at the centres
  // of 256 x 256 cells over the tile, or one byte when they are all the same.
  const WaterMask* waterMask = nullptr;
};

struct QuantizedMeshTileStats {
  std::uint64_t triangles = 0;
  std::uint64_t truthSamples = 0;  // source samples measured (and lattice points without data)
  int truthStride = 1;             // every source sample (1), or every stride-th column and row
  double maxErrorM = 0.0;          // the largest 3-D miss over them, at their drawn positions
};

// The longitude or latitude of a tile boundary: -180 + k * extent or -90 + k * extent, exact
// in binary for every level (extent = 180 / 2^level), so neighbours agree to the bit.
double quantizedMeshTileExtentDeg(int level);

// A tile's mesh before it is quantized: what quantized-mesh tiles and 3D Tiles' glTF tiles
// are made of. Vertices at quantized tile coordinates u, v (0..32767 over the tile, y from the
// south) with their exact ellipsoidal heights, ECEF positions (metres) and the data's unit
// normals (ECEF); triangles counter-clockwise seen from above, in first-use order. Two tiles
// sharing an edge have the same vertices on it, with the same heights to the bit.
struct GeographicTileMesh {
  double westDeg = 0.0, southDeg = 0.0, extentDeg = 0.0;
  std::vector<std::uint16_t> u, v;
  std::vector<float> heightM;
  std::vector<glm::dvec3> ecef;
  std::vector<glm::dvec3> normals;
  std::vector<std::uint32_t> indices;
};

// The mesh of a tile, within options.maxErrorM in 3-D (see above; watermask ignored).
// Errors: a tile outside the scheme, options out of range.
Result<GeographicTileMesh> buildGeographicTileMesh(const LonLatSampler& source,
                                                   const QuantizedMeshTileAddress& address,
                                                   const QuantizedMeshTileOptions& options,
                                                   QuantizedMeshTileStats& stats);

// The mesh quantized into a quantized-mesh tile (heights to 16 bits of the tile's range), with
// its header, oct-encoded normals and water mask. Errors: those of buildGeographicTileMesh.
Result<QuantizedMeshTile> buildQuantizedMeshTile(const LonLatSampler& source,
                                                 const QuantizedMeshTileAddress& address,
                                                 const QuantizedMeshTileOptions& options,
                                                 QuantizedMeshTileStats& stats);

}  // namespace tellus
