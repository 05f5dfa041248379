#pragma once
// RAG's tessellations (seed 004, section 4.2.1 and Figure 13), the CPU twin of
// shaders/rag/tessellate.glsl: a triangle is split according to which of its edges need a
// midpoint, a 3-bit case as the seed's geometry shader builds it:
//
//   bit 0 (kEdge01)  edge v0-v1 (a leg)
//   bit 1 (kEdge12)  edge v1-v2 (the hypotenuse)
//   bit 2 (kEdge02)  edge v0-v2 (a leg)
//
// Right-angled (rag-right, the seed's shader variant 1): a split leg forces the hypotenuse to
// be split too, as in Ulrich's algorithm, so cases 1, 4 and 5 become 3, 6 and 7; when the
// hypotenuse did not need its own split, its midpoint is an invisible T-vertex whose height is
// interpolated from its edge's ends instead of read from the map. Every triangle emitted is a
// right triangle with its right angle at vertex 0, plus, for each invisible T-vertex, a fill
// triangle (v1, m12, v2): zero area in the world, it covers exactly the sliver that float
// rounding opens in screen space between the neighbour's long edge and the two halves, so
// rasterisation stays watertight (without it the crack metric finds pixels there). Its edges
// never need a split (halves of an interpolated edge, and an edge that did not need one), so
// later passes pass it on unchanged. It is left out where its edge reaches behind the near
// plane (rag::fillIsSafe).
//
// Partially oblique (rag, shader variant 2): only edges that need a split are split; cases 1, 4
// and 5 connect the new midpoints to the opposite vertex and emit oblique triangles (the red
// ones of Figure 13), vertex 0 at their largest angle. The other five cases are the
// right-angled ones.
//
// Either way a triangle's edge is split exactly when its own decision says so (or, in the
// right-angled variant, invisibly): two triangles that share an edge and take the same
// decision for it emit the same midpoint, which is why RAG needs no neighbour information.
#include <array>
#include <cstdint>

#include "tellus/dem/height_grid.hpp"
#include "tellus/lod/rag/rag_mesh.hpp"

namespace tellus::rag {

enum class Variant {
  Oblique,      // `rag`: partially-oblique tessellations, screen-space midpoint error
  RightAngled,  // `rag-right`: right-angled tessellations, height-difference criterion
};

inline constexpr std::uint32_t kEdge01 = 1u, kEdge12 = 2u, kEdge02 = 4u;

// The case the variant tessellates for the edges that need a split: `needed` itself for
// Oblique; for RightAngled a needed leg adds kEdge12.
std::uint32_t tessellationCase(Variant variant, std::uint32_t needed);

// Up to five triangles (four and a fill triangle), in the order the geometry shader emits
// them.
inline constexpr int kMaxTessellationTriangles = 5;
struct Tessellation {
  std::array<Triangle, kMaxTessellationTriangles> triangles{};
  int count = 0;
};

// Per edge (v0-v1, v1-v2, v0-v2, as the kEdge* bits), how far a split edge's midpoint goes from
// the interpolated height towards the map's: 1 is the map's height (RefinementSettings::morphBand).
using EdgeSurface = std::array<float, 3>;

// Splits `triangle` for the edges in `needed` (kEdge* bits) with the variant's tessellation.
// Midpoints of needed edges take their height from `grid` (sampleMap with `sampling`), or with `surface`
// below 1 the interpolated height moved that far towards it; an invisible hypotenuse midpoint
// (RightAngled, kEdge12 forced) takes (h1 + h2) * 0.5.
// emitFill: whether an invisible T-vertex gets its fill triangle (rag::fillIsSafe()).
Tessellation tessellate(const Triangle& triangle, std::uint32_t needed, Variant variant,
                        const HeightGrid& grid, bool emitFill = true,
                        const EdgeSurface& surface = {1.0f, 1.0f, 1.0f},
                        MapSampling sampling = MapSampling::Nearest);

}  // namespace tellus::rag
