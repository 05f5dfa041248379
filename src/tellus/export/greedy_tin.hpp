#pragma once
// Greedy insertion of grid samples into a Delaunay triangulation until every sample lies
// within a vertical bound of the mesh (Garland and Heckbert, "Fast Polygonal Approximation of
// Terrains and Height Fields", 1995, algorithm III): start from the grid's two corner
// triangles; each triangle knows its worst sample (largest |mesh - sample|, found by
// rasterising the triangle over the grid); the worst of all is inserted (splitting its
// triangle in three, or the two triangles of the edge it lies on in four), the Delaunay
// property is restored by edge flips, and the changed triangles are rasterised again. The
// bound holds by construction: insertion stops only when no sample misses it. GL-free.
//
// The same insertion works on scattered points (buildScatteredTin): points with integer plane
// coordinates (a quantized-mesh tile's u and v) and a true 3-D position each; a triangle's
// error at a point is the distance between the point's position and the triangle's point at
// the same plane coordinates (the corners' positions mixed with the point's barycentric
// weights). With positions (col * spacingX, row * spacingY, height) that distance is the
// vertical error of the grid version; with ECEF positions it is the gap between the flat
// triangle a client draws between its corners and the curved surface, in 3-D.
#include <cstdint>
#include <span>
#include <vector>

#include <glm/vec3.hpp>

namespace tellus {

struct GreedyTinInput {
  int width = 0, height = 0;             // samples, >= 2 each
  double spacingXM = 1.0, spacingYM = 1.0;  // for the Delaunay circles (ground shape)
  const float* heightsM = nullptr;       // width * height, row-major
  double maxErrorM = 0.0;
  bool keepBorder = false;  // insert every border sample first (tiles meet their neighbours)
};

struct GreedyTin {
  std::vector<std::uint32_t> vertices;  // sample indices (row * width + col)
  std::vector<std::uint32_t> triangles;  // three vertex indices a triangle, counter-clockwise
                                         // with columns right and rows up
  double maxErrorM = 0.0;                // the worst sample's miss at the end
};

GreedyTin buildGreedyTin(const GreedyTinInput& input);

struct ScatteredTinInput {
  // Plane coordinates, >= 0, unique. Points 0..3 are the corners of the rectangle that holds
  // them all, counter-clockwise from (min x, min y); points 4..borderCount-1 lie on its
  // border and are all kept (tiles that must meet their neighbours); the rest lie inside or
  // on the border and are inserted while they miss the mesh by more than the bound.
  std::span<const std::int32_t> x, y;
  std::span<const glm::dvec3> positions;  // per point, metres (any Cartesian frame)
  std::uint32_t borderCount = 4;
  double metresPerUnitX = 1.0, metresPerUnitY = 1.0;  // ground size of a unit (Delaunay circles)
  double maxErrorM = 0.0;
};

// Vertices are point indices. Errors are 3-D distances as above.
GreedyTin buildScatteredTin(const ScatteredTinInput& input);

}  // namespace tellus
