#pragma once
// Image-space quality metrics of one rendered frame, computed on the CPU from read-back
// buffers (GL-free, so they are unit-tested on synthetic frames):
//
// Screen-space error: for each terrain pixel, the world point the renderer drew there is
// reconstructed from its depth; the true surface point at the same ground position (x, y) is
// taken from the full-resolution mesh (HeightGrid::meshHeightAtWorld, the triangles the
// reference renderer draws); both are projected, and their distance in pixels is the pixel's
// error.
//
// Cracks: a renderer draws over a sentinel clear colour; sentinel pixels that lie inside the
// terrain's interior in the reference render (pixels whose 3x3 neighbourhood is all terrain
// there) are holes, cracks or T-junction gaps.
#include <cstdint>
#include <functional>
#include <vector>

#include <glm/vec3.hpp>

#include "tellus/core/camera.hpp"
#include "tellus/core/depth_image.hpp"
#include "tellus/core/rgb_image.hpp"
#include "tellus/dem/height_grid.hpp"

namespace tellus {

struct ErrorSummary {
  std::uint64_t pixels = 0;  // terrain pixels measured
  double meanPx = 0.0;
  double p95Px = 0.0;
  double p99Px = 0.0;
  double maxPx = 0.0;
};

struct ScreenSpaceError {
  ErrorSummary summary;
  std::vector<float> errorPx;  // per pixel, row 0 = top; negative where there is no terrain
};

// The true surface point for a point drawn at `drawn` (world coordinates of the view: the flat
// world's metres, or ECEF on the globe); false where the truth has no data (such pixels are
// not measured).
using TrueSurfaceFn = std::function<bool(const glm::dvec3& drawn, glm::dvec3& surface)>;

// `view` must be the frame's view (same size as the depth image); `exaggeration` the vertical
// exaggeration the frame was drawn with (the truth is scaled the same way).
ScreenSpaceError measureScreenSpaceError(const DepthImage& depth, const ViewSetup& view,
                                         const HeightGrid& truth, double exaggeration = 1.0);
// The same against any truth (the globe's: globe_surface.hpp).
ScreenSpaceError measureScreenSpaceError(const DepthImage& depth, const ViewSetup& view,
                                         const TrueSurfaceFn& trueSurface);

// Popping: the screen-space displacement of the surface caused by a change of level of detail
// alone. `current` and `previousLod` are depth images of the same view drawn with this frame's
// geometry and with the previous frame's (TerrainRenderer::drawPreviousSelection). At a pixel
// drawn in both, each render's point is moved vertically onto the true surface at its ground
// position, as for the screen-space error, and the distance in pixels between the two true
// points' projections is the pixel's popping: the change of the pixel's screen-space error
// vector, i.e. how far the feature seen there jumps. Identical depths score 0; pixels drawn in
// one render only (silhouette and culling changes) are not measured (negative).
ScreenSpaceError measurePopping(const DepthImage& current, const DepthImage& previousLod,
                                const ViewSetup& view, const HeightGrid& truth,
                                double exaggeration = 1.0);
ScreenSpaceError measurePopping(const DepthImage& current, const DepthImage& previousLod,
                                const ViewSetup& view, const TrueSurfaceFn& trueSurface);

// Terrain with several surfaces per (x, y) (material stacks) is measured against a depth
// image of the truth instead: depth_truth_error.hpp.

// Mean, 95th percentile and max of non-negative values (negative ones are ignored).
ErrorSummary summariseErrors(const std::vector<float>& values);

// Green (0 px) through yellow to red (>= 10 px) per terrain pixel, as in the RAG thesis; sky
// (no terrain) stays the colour of `background`.
RgbImage errorImage(const ScreenSpaceError& error, int width, int height,
                    const RgbImage& background);

struct CrackReport {
  std::uint64_t crackPixels = 0;
  // Background inside the reference's terrain but connected to the open sky: a silhouette lower
  // than the reference's (LOD simplification of ridges), reported apart from cracks; also, for
  // closed solids, enclosed background seen through open air (excludeOpenAirGaps).
  std::uint64_t silhouettePixels = 0;
  std::vector<std::uint8_t> mask;  // 1 where a crack pixel is, row 0 = top
};

// Terrain coverage of a reference frame: 1 where its depth buffer holds a drawn surface.
std::vector<std::uint8_t> coverageFromDepth(const DepthImage& reference);

// Cracks: pixels of `image` equal to `sentinel` (the clear colour: background shows through)
// inside the interior (3x3) of `referenceCoverage` and enclosed by the image's own terrain, i.e.
// not connected through background pixels to background outside the reference's terrain or to
// the image border. Holes in a surface are enclosed; a lowered silhouette opens onto the sky and
// is counted as silhouettePixels instead.
CrackReport detectCracks(const RgbImage& image, const std::uint8_t sentinel[3],
                         const std::vector<std::uint8_t>& referenceCoverage);

// Closed solids (stack terrain) only: a background pixel whose view ray crosses no back face of
// the solid (`backFaceCoverage` 0: the frame's geometry drawn with front faces culled covers
// nothing there) never entered the solid, so it was reached through open air, e.g. a gap between
// LOD-simplified rock filaments where the reference has rock. A hole in the surface lets the ray
// into the solid, which it leaves through a back face. Moves such crack pixels to
// silhouettePixels (they change the outline, they are no hole) and clears them from the mask.
void excludeOpenAirGaps(CrackReport& report, const std::vector<std::uint8_t>& backFaceCoverage);

// `image` with crack pixels painted magenta and a 2-pixel ring around each, to find them.
RgbImage markCracks(const RgbImage& image, const CrackReport& cracks);

}  // namespace tellus
