#pragma once
// An adaptive triangle mesh of a regular height grid within a given vertical error: the grid's
// two-triangles-a-cell mesh simplified by meshoptimizer's edge collapses, then checked against
// every grid sample. The simplifier measures a 3D quadric error, which on steep slopes is less
// than the vertical one, so the target is tightened until the measured vertical error (the
// largest |mesh height - sample height| over all samples) is within the bound: the bound is
// guaranteed by measurement, not assumed. GL-free.
//
// meshoptimizer works in single precision on the mesh scaled to a unit cube, where a metre of
// height on a 20 km grid is lost in the quadrics' rounding (it then rates collapses error-free
// that miss samples by metres, and no target meets a tight bound). Grids larger than
// kTerrainMeshBlockSamples a side are therefore simplified in blocks of that many samples
// that keep their borders (extra vertices along the block edges: the price of the bound).
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

inline constexpr int kTerrainMeshBlockSamples = 33;

struct TerrainMeshOptions {
  double maxErrorM = 1.0;   // the largest vertical error allowed, metres (>= 0)
  bool lockBorder = false;  // keep every border sample (tiles that must meet their neighbours;
                            // grids cut into blocks always keep theirs)
};

// A mesh whose vertices are grid samples.
struct TerrainMesh {
  std::vector<std::uint32_t> samples;  // per vertex: the sample's index (row * width + col)
  std::vector<std::uint32_t> indices;  // three vertex indices a triangle, counter-clockwise
                                       // with columns to the right and rows up
  double maxErrorM = 0.0;              // measured: max |mesh - sample| over every sample
  int simplifierRuns = 0;              // meshoptimizer calls it took to meet the bound
};

// Errors: a grid under 2 x 2 samples, heights not width * height, a negative or non-finite
// bound, non-finite heights, or more than 2^32 samples.
Result<TerrainMesh> buildTerrainMesh(const GridHeights& grid, const TerrainMeshOptions& options);

// The largest |mesh height - sample height| over every sample of `grid` covered by the mesh
// (each sample is interpolated on a triangle that contains it); infinity when a sample is
// covered by no triangle (the mesh has a hole).
double measureVerticalError(const GridHeights& grid, std::span<const std::uint32_t> samples,
                            std::span<const std::uint32_t> indices);

}  // namespace tellus
