#pragma once
// The mesh RAG refines (seed 004, sections 4.2-4.4), GL-free: triangles whose vertices are
// (u, v, h) in the height map's own units, laid out exactly as the transform feedback buffers
// hold them on the GPU.
//
//   u, v   sample coordinates: u east from the western column (0 .. width - 1), v north from the
//          southern row (0 .. height - 1). The coarse mesh's vertices and every midpoint of
//          them are computed as (a + b) * 0.5 in float, which is exact and commutative, so two
//          triangles sharing an edge compute bit-identical midpoints on the CPU and the GPU.
//   h      height in metres: from the height map (nearest sample, as the seed requires) for
//          coarse vertices and for midpoints of edges that needed a split; interpolated,
//          (h_a + h_b) * 0.5, for the invisible T-vertices of the right-angled variant.
//
// Vertex order (the seed's rule, section 5.1.2): counter-clockwise seen from above (x east,
// y north) and the hypotenuse, the edge opposite the right angle, between the second and third
// vertex. Every tessellation keeps this order for the triangles it emits, so right-angled
// triangles always have their right angle at vertex 0.
#include <array>
#include <cstdint>
#include <vector>

#include <glm/vec3.hpp>

#include "tellus/core/result.hpp"
#include "tellus/dem/height_grid.hpp"

namespace tellus::rag {

using Vertex = glm::vec3;  // (u, v, h): samples, samples, metres

struct Triangle {
  std::array<Vertex, 3> v;  // v[0] the right angle (for right triangles), v[1]-v[2] hypotenuse
};
static_assert(sizeof(Triangle) == 36, "three vec3 as in the transform feedback buffer");

// Vertices per side of the coarse mesh: the seed measures 20, 40 and 80 (Figures 25 and 28);
// the default, 80, with 6 passes at 0.35 px is chosen in docs/rag.md ("Choosing the defaults").
inline constexpr int kDefaultCoarseVertices = 80;
inline constexpr int kMinCoarseVertices = 2;
inline constexpr int kMaxCoarseVertices = 1025;

// The height map as RAG samples it: nearest sample, clamped to the grid (texelFetch on the
// GPU). u, v as above; the result in metres.
float sampleNearest(const HeightGrid& grid, float u, float v);

// The map's surface as the reference draws it (HeightGrid::meshHeightAtWorld): each cell two
// planar triangles split along its south-west to north-east diagonal; clamped to the grid.
// Equal to sampleNearest at samples; at a cell's centre the mean of its south-west and
// north-east samples. Float, in the order shaders/rag/rag_common.glsl computes it.
float sampleSurface(const HeightGrid& grid, float u, float v);

// How refinement reads heights between the coarse vertices.
enum class MapSampling {
  Nearest,  // the nearest sample (the seed's; with the seed's unaligned coarse mesh)
  Surface,  // the reference's triangles (sampleSurface; with the aligned coarse mesh)
};
float sampleMap(const HeightGrid& grid, float u, float v, MapSampling sampling);

// A uniform vertices x vertices grid over the whole height map (both directions spread over
// width - 1 and height - 1 samples), heights sampled before the recursion starts. Each cell is
// split along a diagonal that alternates like a checkerboard (a 4-8 mesh), giving two right
// triangles per cell in the order above. Error when vertices is outside
// [kMinCoarseVertices, kMaxCoarseVertices] or the grid has fewer than 2 samples a side.
Result<std::vector<Triangle>> buildCoarseMesh(const HeightGrid& grid, int vertices);

// The same aligned to the samples (beyond the seed; the default since issue 45): cells of P x P
// samples, P the power of two nearest to the unaligned cell size, so every vertex the passes
// create lies on a sample and log2(P) passes reach the map's full resolution with the map's own
// heights. Every cell is split along its south-west to north-east diagonal, as the reference's
// cells are (refinement then splits the other diagonals of single cells where they show:
// rag_refinement.hpp).
// The grid has ceil((width - 1) / P) + 1 by ceil((height - 1) / P) + 1 vertices; the last
// column and row may be narrower (clamped to the grid's edge). Unaligned meshes put vertices
// between samples, where nearest sampling moves them by up to half a sample: invisible from
// afar, hundreds of pixels of error from 2 m above the ground (docs/rag.md, the Korea walk).
Result<std::vector<Triangle>> buildAlignedCoarseMesh(const HeightGrid& grid, int vertices);
// The cell size in samples buildAlignedCoarseMesh uses for `vertices` a side.
int alignedCellSamples(const HeightGrid& grid, int vertices);

}  // namespace tellus::rag
