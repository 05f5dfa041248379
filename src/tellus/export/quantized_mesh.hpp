#pragma once
// Cesium's quantized-mesh-1.0 terrain tile format
// (https://github.com/CesiumGS/quantized-mesh): encoding and decoding of one tile. GL-free.
//
// Layout, little-endian: a 88-byte header (centre, height range, bounding sphere and horizon
// occlusion point, all ECEF metres except the occlusion point, which is in the ellipsoid-scaled
// frame); the vertex count and the u, v and height arrays (uint16, 0..32767, zig-zag delta
// coded); padding to the index size; the triangle count and the indices (high-water-mark
// coded, 16 bit when there are at most 65536 vertices, else 32 bit); the west, south, east and
// north edge vertex lists (not coded); then extensions (here: 1, oct-encoded vertex normals;
// 2, the water mask; 4, metadata: a uint32 length and that many bytes of JSON, whose
// "available" lists the tile ranges of the next levels under this tile).
#include <array>
#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

#include "tellus/core/result.hpp"

namespace tellus {

inline constexpr int kQuantizedMeshMaxCoordinate = 32767;
inline constexpr std::uint8_t kQuantizedMeshOctNormalsExtension = 1;
inline constexpr std::uint8_t kQuantizedMeshWaterMaskExtension = 2;
inline constexpr std::uint8_t kQuantizedMeshMetadataExtension = 4;
inline constexpr std::size_t kQuantizedMeshWaterMaskSide = 256;

struct QuantizedMeshHeader {
  glm::dvec3 centreEcef{0.0};
  float minHeightM = 0.0f;
  float maxHeightM = 0.0f;
  glm::dvec3 boundingSphereCentreEcef{0.0};
  double boundingSphereRadiusM = 0.0;
  glm::dvec3 horizonOcclusionPoint{0.0};  // ellipsoid-scaled frame
};

struct QuantizedMeshTile {
  QuantizedMeshHeader header;
  // Per vertex: u west->east, v south->north, height minHeight->maxHeight, each 0..32767.
  std::vector<std::uint16_t> u, v, height;
  std::vector<std::uint32_t> indices;  // three a triangle, counter-clockwise seen from above
  // Vertices on each edge (u == 0, v == 0, u == 32767, v == 32767).
  std::vector<std::uint32_t> westEdge, southEdge, eastEdge, northEdge;
  // Oct-encoded unit normals (ECEF), two bytes a vertex; empty when the tile has none.
  std::vector<std::array<std::uint8_t, 2>> octNormals;
  // The water mask (0 land .. 255 water): empty (none), one byte (the whole tile), or 256 x 256
  // bytes over the tile, row 0 north, column 0 west.
  std::vector<std::uint8_t> waterMask;
  // The metadata extension's JSON text (UTF-8), empty when the tile has none. Not parsed here.
  std::string metadataJson;
};

// The tile's bytes. The indices must reference vertices in order of first use (each index at
// most one more than the largest before it), as high-water-mark coding needs: reorder with
// meshopt_optimizeVertexFetch first. Errors: mismatched array sizes, coordinates over 32767,
// indices out of range or not in first-use order, a water mask of neither 1 nor 65536 bytes.
Result<std::vector<std::byte>> encodeQuantizedMesh(const QuantizedMeshTile& tile);
// Parses a tile, checking every size and index against the buffer. `where` names the tile in
// errors.
Result<QuantizedMeshTile> decodeQuantizedMesh(std::span<const std::byte> bytes,
                                              std::string_view where);

// Oct encoding of a unit vector into two bytes (Cesium's AttributeCompression.octEncode) and
// back.
std::array<std::uint8_t, 2> octEncodeNormal(const glm::dvec3& unit);
glm::dvec3 octDecodeNormal(std::array<std::uint8_t, 2> encoded);

// Cesium's horizon culling point for a tile: the point in the ellipsoid-scaled frame along
// the direction of `directionEcef` from which every one of `pointsEcef` is hidden exactly when
// it is (EllipsoidalOccluder.computeHorizonCullingPointFromVertices on WGS84). Returns false
// when there is none (a tile spanning too much of the globe); the caller then writes the
// tile's centre scaled, which Cesium treats as never occluded only near it.
bool horizonOcclusionPoint(const glm::dvec3& directionEcef, std::span<const glm::dvec3> pointsEcef,
                           glm::dvec3& point);

}  // namespace tellus
