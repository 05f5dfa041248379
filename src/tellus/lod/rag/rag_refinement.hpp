#pragma once
// RAG's refinement loop on the CPU (seed 004, sections 4.2.2 and 4.4): the reference the GPU
// renderer (render/rag/) is tested against, with the same function names as
// shaders/rag/refine.geom. Per pass, every triangle is dropped when it is certainly outside
// the view frustum (early clipping), otherwise its three edges are decided and it is
// tessellated (rag_tessellation.hpp); the output of a pass is the input of the next.
//
// Positions are projected as the shaders do, in float: the vertex's offset from the camera in
// sample units, scaled to metres (and the height exaggerated), then the camera-relative
// view-projection matrix. Offsets from the camera stay small where precision matters, near the
// viewer, whatever the terrain's extent.
#include <cstdint>
#include <vector>

#include <glm/mat4x4.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include "tellus/core/camera.hpp"
#include "tellus/dem/height_grid.hpp"
#include "tellus/lod/rag/rag_mesh.hpp"
#include "tellus/lod/rag/rag_tessellation.hpp"

namespace tellus::rag {

// What the edge decisions and the clipping test need of a frame, in float as uploaded.
struct RefinementView {
  glm::mat4 clipFromRelative{1.0f};  // ViewSetup::relativeViewProjection()
  glm::vec3 cameraGrid{0.0f};        // the camera in (u, v, h) units: samples, samples, metres
  glm::vec3 gridScale{1.0f};         // metres per unit: (spacing x, spacing y, exaggeration)
  glm::vec2 viewportPx{1.0f};        // width, height
  // Pixels a metre spans seen face-on at a distance of one metre: height / (2 tan(fovY / 2)).
  float focalPx = 1.0f;
  float nearM = 1.0f, farM = 1000.0f;
  float minHeightM = 0.0f, maxHeightM = 0.0f;  // the height map's range (conservative clipping)

  static RefinementView create(const ViewSetup& view, double spacingXM, double spacingYM,
                               HeightRange heights, float verticalExaggeration);
  // The same for a grid (scans its heights for the range).
  static RefinementView create(const ViewSetup& view, const HeightGrid& grid,
                               float verticalExaggeration) {
    return create(view, grid.spacingXM, grid.spacingYM, grid.heightRange(), verticalExaggeration);
  }
};

// The renderer's default for RefinementSettings::edgeLengthPx: on the Korea walk (1280 x 720)
// SSE p99 0.22 -> 0.14 px with 8 % more triangles; on a generated steep range's walk popping
// p99 1.53 -> 0.12 px (docs/rag.md). From above it hardly ever fires (the flyover's triangles
// span a few pixels).
inline constexpr float kDefaultEdgeLengthPx = 16.0f;

struct RefinementSettings {
  Variant variant = Variant::Oblique;
  // Oblique: an edge is split when its midpoint's height from the map moves it on screen by
  // at least this many pixels against the interpolated midpoint (the seed's pixelEdge).
  // 0.5 px with 3 probes: SSE p99 0.97 px on the Korea flyover at 1280 x 720 (the seed's
  // 0.35 px at the midpoint alone: 1.9 px with 0.8 times the triangles; docs/rag.md).
  float pixelEdge = 0.5f;
  // Oblique, beyond the seed: points of the edge whose error is measured, 1 (the midpoint, the
  // seed's) or 3 (its quarter points too, the largest error taken). The midpoint alone is blind
  // to detail beside it: a midpoint that happens to lie on the surface stops the refinement.
  int edgeProbes = 3;
  // RightAngled: an edge is split when |h_a - h_b| * depthWeight exceeds this (metres), with
  // depthWeight falling linearly from 1 at the near plane to depthDetail at the far plane
  // (the seed's "depth detail": 1 = the same everywhere, 0 = nothing is split at the far plane).
  float heightDifferenceM = 60.0f;  // 4 % of N37E127's relief (docs/rag.md)
  float depthDetail = 0.5f;
  bool earlyClip = true;
  // Oblique, beyond the seed: a split edge's new vertex enters at the interpolated midpoint and
  // reaches the map's height once the midpoint error passes pixelEdge (1 + morphBand): its
  // height is interpolated + s (map - interpolated), s = (error - pixelEdge) / (pixelEdge
  // morphBand) clamped to [0, 1]. The surface then moves continuously with the camera (no pop
  // when an edge starts to split), and the error left at a split vertex never exceeds pixelEdge
  // (for bands up to 1). 0: the seed's (the map's height at once).
  float morphBand = 0.0f;
  // Oblique, beyond the seed: an edge is also split when its length, seen face-on from the
  // distance of its midpoint, spans at least this many pixels (0: never; the seed's). The probes
  // see only the edge's own samples; a long edge near the eye hides samples between edges that
  // the camera sees from a few metres, so near the ground every edge is split down to single
  // samples, where (with the aligned coarse mesh) the surface is the map's own triangles. The
  // renderer's default is kDefaultEdgeLengthPx.
  float edgeLengthPx = 0.0f;
  // How heights between the coarse vertices are read: the seed's nearest sample, or (with the
  // aligned coarse mesh) the reference's triangles. With Surface, a single cell's diagonal
  // from north-west to south-east, which the 4-8 bisections leave in every second cell, is an
  // edge like any other: its midpoint is the cell's centre on the reference's diagonal, and
  // splitting it gives the cell the reference's own surface (from 2 m above the ground the
  // other diagonal is tens of pixels off).
  MapSampling sampling = MapSampling::Nearest;
};

// Clip-space position of a vertex, as the shaders compute it.
glm::vec4 clipPosition(const RefinementView& view, const Vertex& vertex);

// The quantity an edge decision compares with its threshold: the midpoint's screen error in
// pixels (Oblique) or the weighted height difference in metres (RightAngled). Symmetric in
// a and b bit for bit: the ends are put in a canonical order first.
struct EdgeMeasure {
  float value = 0.0f;
  float threshold = 0.0f;
  bool decided = false;  // true when the edge was decided without the measure (see below)
  bool split = false;    // the decision
  float surface = 1.0f;  // a split edge's midpoint: how far towards the map's height (morphBand)
  // The edge-length test (RefinementSettings::edgeLengthPx), when it ran: the edge's face-on
  // length in pixels and the threshold (0 when it did not run).
  float lengthPx = 0.0f;
  float lengthThresholdPx = 0.0f;
};
// An edge whose ends lie within one sample of each other in both directions is never split
// (the map holds nothing between them: the seed's equation 3), but for a cell's north-west to
// south-east diagonal with MapSampling::Surface; an Oblique edge whose midpoint
// lies behind the near plane is always split (it passes by the eye), and one whose face-on length
// reaches edgeLengthPx is split without probing.
EdgeMeasure measureEdge(const RefinementView& view, const RefinementSettings& settings,
                        const HeightGrid& grid, const Vertex& a, const Vertex& b);
bool edgeNeedsSplit(const RefinementView& view, const RefinementSettings& settings,
                    const HeightGrid& grid, const Vertex& a, const Vertex& b);

// The needed-edge bits (kEdge*) of a triangle. With closestDecision, lowers it to the
// relative margin |value - threshold| / threshold of each edge decided by its measure.
std::uint32_t neededEdges(const RefinementView& view, const RefinementSettings& settings,
                          const HeightGrid& grid, const Triangle& triangle,
                          float* closestDecision = nullptr, EdgeSurface* surface = nullptr);

// Whether a fill triangle over the edge a-b may be drawn: both ends in front of the near plane
// (rag_tessellation.hpp).
bool fillIsSafe(const RefinementView& view, const Vertex& a, const Vertex& b);

// Early clipping keeps what lies within kClipMargin * |w| outside a plane: float rounding, here
// and in other renderers' arithmetic, must not drop a triangle the rasteriser would draw.
inline constexpr float kClipMargin = 1e-3f;

// True when every surface the triangle can ever be refined into lies outside one frustum plane:
// the prism over its (u, v) footprint from the map's lowest to its highest height is tested
// (midpoints stay inside the footprint, heights inside the map's range).
bool isOutsideFrustum(const RefinementView& view, const Triangle& triangle);

struct PassStats {
  std::uint64_t input = 0;    // triangles read
  std::uint64_t clipped = 0;  // dropped by early clipping
  std::uint64_t output = 0;   // triangles written
};

struct RefinementResult {
  std::vector<Triangle> triangles;
  std::vector<PassStats> passes;
  // The smallest |value - threshold| / threshold over the decisions taken by a measure: how
  // close the frame came to a decision that float rounding could flip (tests compare the GPU
  // with this reference only when it is comfortably large).
  float closestDecision = 1e30f;
};

// `passes` refinement passes over `mesh` (0 returns the mesh as it is, as the renderer draws
// the coarse mesh without a geometry shader).
RefinementResult refine(const std::vector<Triangle>& mesh, const HeightGrid& grid,
                        const RefinementView& view, const RefinementSettings& settings,
                        int passes);

}  // namespace tellus::rag
