#pragma once
// The screen-space error of 3D terrain (material stacks, seed 003), whose truth is a depth image
// of the same view drawn by the ground-truth renderer, not a height per ground position.
//
// The flat world's measure (frame_metrics.hpp) moves each drawn point vertically onto the true
// surface and reports how far that true point lies from the pixel on screen: how far the
// feature seen there is displaced. Here the truth is known only where the truth image sees it,
// and a surface may overhang. So each truth pixel q in a window around P's pixel p contributes
// its world point T and its surface normal n (from the truth's neighbouring pixels), and P is
// moved onto that tangent plane: straight down or up as in the flat world, or along n where the
// plane is steeper than 78 degrees (a wall, which a vertical line may never meet). A plane is
// extended at most (|q - p| + 1.5) pixels from q, on screen and in the world (in units of the
// spacing of q's points, so a plane seen at a grazing angle does not reach far along the rays).
// Of the candidates, the one least extended wins (within 0.75 px counts as q itself), then the
// one nearest P. The pixel's error is the distance in pixels from p to the foot's projection. On
// a plane this is exactly the flat world's measure; on hills drawn raised it matches the flat
// world's vertical displacement to 0.04 px at p95 (StackHarnessTest).
//
// Where no candidate in the window qualifies (a displacement larger than the window, or a drawn
// point whose true surface is hidden in the truth image), the error is the distance between
// the two points along the pixel's ray at the nearer one's distance, converted to pixels as the
// seed's screen-space extent, delta * height / (2 d tan(fovY / 2)): an upper bound, which
// grows as 1 / sin of the angle between the ray and the surface, so it is kept for those
// pixels only.
//
// Pixels drawn in one image only are not measured (negative): background in the truth's
// interior is a crack (detectCracks), terrain over the truth's sky a silhouette change.
// Identical depths score exactly 0. The same measure between a frame's render and its previous
// selection's render is the popping of 3D terrain.
#include "tellus/core/camera.hpp"
#include "tellus/core/depth_image.hpp"
#include "tellus/eval/frame_metrics.hpp"

namespace tellus {

// Half the side of the candidate window, in pixels: displacements up to about twice this are
// measured as displacements; larger ones fall back to the distance along the ray.
inline constexpr int kDepthTruthWindowPx = 5;

// `drawn` and `truth`: depth images of `view` (the same size; otherwise nothing is measured).
ScreenSpaceError measureDepthTruthError(const DepthImage& drawn, const DepthImage& truth,
                                        const ViewSetup& view);

}  // namespace tellus
