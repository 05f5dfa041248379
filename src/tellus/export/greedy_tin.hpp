#pragma once
// Greedy insertion of grid samples into a Delaunay triangulation until every sample lies
// within a vertical bound of the mesh (Garland and Heckbert, "Fast Polygonal Approximation of
// Terrains and Height Fields", 1995, algorithm III): start from the grid's two corner
// triangles; each triangle knows its worst sample (largest |mesh - sample|, found by
// rasterising the triangle over the grid); the worst of all is inserted (splitting its
// triangle in three, or the two triangles of the edge it lies on in four), the Delaunay
// property is restored by edge flips, and the changed triangles are rasterised again. The
// bound holds by construction: insertion stops only when no sample misses it. GL-free.
#include <cstdint>
#include <vector>

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

}  // namespace tellus
