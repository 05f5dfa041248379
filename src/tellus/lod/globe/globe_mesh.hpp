#pragma once
// The globe reference's mesh (GL-free): every sample of a latitude/longitude grid as a vertex on
// the WGS84 ellipsoid, cut into chunks of chunkQuads x chunkQuads cells for culling and buffers.
//
// Positions are ECEF in double, split into whole metres (int32) and the fraction of a metre
// (float, 6e-8 m steps), so the GPU forms positions relative to the eye exactly where it
// matters: (whole - eyeWhole) in integers, which no compiler reassociates, plus (fraction -
// eyeFraction); sub-millimetre precision anywhere on Earth, and a sample shared by two chunks
// has the same bits in both (no cracks between chunks). (Two floats, high and low, were tried
// first: llvmpipe folded the eye's two halves together despite `precise` and lost the low one.)
//
// Heights: the grid's heights are above the geoid (SRTM, ETOPO); with a geoid the vertex sits at
// the ellipsoidal height H + N, without one at H (the error is then the undulation, up to 107 m).
// A grid spanning all 360 degrees of longitude gets its first column repeated east of its last,
// closing the seam at the antimeridian. Normals are per vertex, from the neighbouring samples'
// ECEF positions, expressed in the vertex's own east-north-up frame (so "steep" and "lit" mean
// what they mean on a flat map).
#include <cstdint>
#include <vector>

#include <glm/common.hpp>
#include <glm/vec3.hpp>
#include <glm/ext/vector_int3.hpp>

#include "tellus/core/aabb.hpp"
#include "tellus/core/result.hpp"
#include "tellus/dem/geoid.hpp"
#include "tellus/dem/height_grid.hpp"

namespace tellus::globe {

struct GlobeVertex {  // 32 bytes, as the vertex buffer holds it
  glm::ivec3 whole{0};       // ECEF, whole metres (floor)
  glm::vec3 fraction{0.0f};  // ECEF minus whole, in [0, 1) metres
  std::uint32_t normal = 0;  // unit normal in the local ENU frame, GL_INT_2_10_10_10_REV
  float heightM = 0.0f;      // above the geoid (the tint)
};
static_assert(sizeof(GlobeVertex) == 32);

struct GlobeChunk {
  int vertsX = 0, vertsY = 0;  // row-major, row 0 north
  std::vector<GlobeVertex> vertices;
  Aabb ecefBounds;  // of the vertices, for culling
};

struct GlobeMesh {
  std::vector<GlobeChunk> chunks;
  std::uint64_t vertexCount = 0;
  std::uint64_t triangleCount = 0;
  bool wrapsLongitude = false;  // a seam column was added at the antimeridian
};

// Latitude and longitude (degrees) of sample (col, row) of a geographic grid (the sample's
// centre, GDAL's pixel-is-area convention).
double sampleLatitudeDeg(const HeightGrid& grid, double row);
double sampleLongitudeDeg(const HeightGrid& grid, double col);

// Errors: a grid without a geographic CRS and geotransform, or one reaching beyond +-90 degrees.
//
// `skirtM` > 0 adds a skirt: a ring of vertices around the grid at its edge samples' latitude and
// longitude, `skirtM` metres lower, with their normals and tints. The ring makes the chunks one
// vertex wider on every side (vertsX, vertsY count it) so that the grid's own index pattern
// draws the skirt as walls hanging from the edges; it hides the gaps where this mesh meets a
// neighbour drawn at another resolution (T-junctions) as long as they are under `skirtM` deep.
// A grid wrapping all longitudes takes no skirt (error).
Result<GlobeMesh> buildGlobeMesh(const HeightGrid& grid, const Geoid* geoid, int chunkQuads,
                                 double skirtM = 0.0);

// The split of an ECEF position, and back.
inline void splitEcef(const glm::dvec3& ecef, glm::ivec3& whole, glm::vec3& fraction) {
  const glm::dvec3 floor = glm::floor(ecef);
  whole = glm::ivec3(floor);
  fraction = glm::vec3(ecef - floor);
}
inline glm::dvec3 vertexEcef(const GlobeVertex& v) {
  return glm::dvec3(v.whole) + glm::dvec3(v.fraction);
}
// The packed normal back as a unit vector (tests).
glm::vec3 unpackNormal(std::uint32_t packed);

}  // namespace tellus::globe
