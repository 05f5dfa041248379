#pragma once
// Geometry image warping (seed 004 section 2.4; Dachsbacher & Stamminger 2004), on the CPU each
// frame: the sketch map (the height grid resampled over a rectangle enclosing the view's
// footprint on the terrain), its importance map, the row-then-column piecewise-linear warp, and
// the warped geometry image (size x size vertices with their heights) drawn as one quad mesh.
//
// Importance of a sketch sample, after the paper's three criteria: distance (1 / distance to the
// eye), surface orientation (slope, and how squarely the surface faces the eye) and the frustum
// (samples outside it keep a small share). The warp treats each row as a piecewise-linear
// function and moves its samples so that every interval holds the same share of the row's
// importance (inverse of the cumulative importance), then does the same along the warped
// columns, with one distribution for all columns (from each row's total importance): rows stay
// horizontal and monotonic in x, so no quad folds over (the paper's per-column distribution can
// shear neighbouring columns across each other), and the grid's four corners and its borders
// stay on the region's border. The paper gives no error bound: the
// warped grid resamples the terrain, and it "swims" as the view moves (both are measured).
#include <cstdint>
#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "tellus/core/result.hpp"
#include "tellus/dem/height_grid.hpp"
#include "tellus/lod/lod_view.hpp"

namespace tellus::giw {

struct GiwSettings {
  int size = 257;                // geometry image side, vertices
  float slopeWeight = 4.0f;      // importance of steep over flat ground (0: distance only)
  float uniformShare = 0.1f;     // share of every row's and column's samples spread evenly
  float outsideImportance = 0.05f;  // importance of samples outside the frustum, relative
};

// An axis-aligned rectangle of the grid, in grid units (x east, y north, samples).
struct Region {
  glm::dvec2 min{0.0}, max{0.0};
};

// The rectangle of the terrain the view can see: the frustum's footprint on the plane of the
// terrain's lowest height `lowestM` (grid.heightRange().minM, computed once by the caller),
// clamped to the grid (the whole grid when the footprint is unbounded).
Region viewRegion(const HeightGrid& grid, float lowestM, const ViewSetup& view, float exaggeration);

// The importance of size x size sketch samples spread evenly over `region` (row-major, row 0
// at region.min.y), each > 0.
std::vector<float> importanceMap(const HeightGrid& grid, const Region& region, const LodView& view,
                                 const GiwSettings& settings);

// The warp of a size x size grid of unit spacing by `importance`: the warped position of each
// vertex in sketch units ([0, size - 1]^2), rows first then columns.
std::vector<glm::dvec2> warpRowsThenColumns(const std::vector<float>& importance, int size, float uniformShare);

// The warped grid over `region` with heights from the grid: (x, y, height) in grid units and
// metres, row-major. Timing of each step in the report.
struct GeometryImage {
  int size = 0;
  Region region;
  std::vector<glm::vec3> vertices;
  std::vector<float> density;  // warped sample density relative to the even grid (the LOD tint)
  double importanceMs = 0.0, warpMs = 0.0, resampleMs = 0.0;
};
GeometryImage buildGeometryImage(const HeightGrid& grid, float lowestM, const ViewSetup& view, float exaggeration,
                                 const GiwSettings& settings);

// Errors: settings out of range (size 9..2049, weights >= 0, share in [0, 1]).
Status checkSettings(const GiwSettings& settings);

}  // namespace tellus::giw
