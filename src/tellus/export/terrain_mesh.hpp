#pragma once
// An adaptive triangle mesh of a regular height grid within a given vertical error: samples
// inserted greedily, worst first, into a Delaunay triangulation until none misses the mesh by
// more than the bound (greedy_tin.hpp; Garland and Heckbert 1995), then measured again over
// every sample. The bound holds by construction and by measurement. GL-free.
#include <cstdint>
#include <span>
#include <vector>

#include "tellus/core/result.hpp"

namespace tellus {

// Heights on a regular grid: width x height samples, row-major, row 0 first; sample (col, row)
// lies at (col * spacingX, row * spacingY) in a plane, metres (the row axis may point north or
// south: only the cell shapes matter).
struct GridHeights {
  int width = 0;
  int height = 0;
  double spacingXM = 1.0;
  double spacingYM = 1.0;
  std::span<const float> heightsM;
};

struct TerrainMeshOptions {
  double maxErrorM = 1.0;   // the largest vertical error allowed, metres (>= 0)
  bool lockBorder = false;  // keep every border sample (tiles that must meet their neighbours)
};

// A mesh whose vertices are grid samples.
struct TerrainMesh {
  std::vector<std::uint32_t> samples;  // per vertex: the sample's index (row * width + col)
  std::vector<std::uint32_t> indices;  // three vertex indices a triangle, counter-clockwise
                                       // with columns to the right and rows up
  double maxErrorM = 0.0;              // measured: max |mesh - sample| over every sample
};

// Errors: a grid under 2 x 2 samples, heights not width * height, a negative or non-finite
// bound, non-finite heights, or more than 2^32 samples.
Result<TerrainMesh> buildTerrainMesh(const GridHeights& grid, const TerrainMeshOptions& options);

// Reorders the triangles for the GPU's vertex cache (meshoptimizer) and renumbers the vertices
// in order of first use: what vertex fetch likes and quantized-mesh's high-water-mark index
// coding needs.
void orderForRendering(TerrainMesh& mesh);

// The largest |mesh height - sample height| over every sample of `grid` covered by the mesh
// (each sample is interpolated on a triangle that contains it); infinity when a sample is
// covered by no triangle (the mesh has a hole).
double measureVerticalError(const GridHeights& grid, std::span<const std::uint32_t> samples,
                            std::span<const std::uint32_t> indices);

}  // namespace tellus
