#pragma once
// RINGO (seed 002): a block's static mesh, what its GPU buffer holds. GL-free; the CPU reference
// of the renderer's vertex shader.
//
// Positions are ECEF split into whole metres and the fraction (as the globe reference's,
// lod/globe/globe_mesh.hpp): the GPU forms them relative to the eye exactly, and a point two
// blocks share gets the same bits in both, so shared edges are watertight. (Positions relative
// to each block's centre in float were tried first: the same point came out of two blocks
// rounded differently, and a pinhole opened at a join seen from orbit.) Heights are the store's
// (above the geoid); with a geoid the vertex sits at the ellipsoidal height H + N.
//
// Crack-free joins between rings (the seed is silent on them; skirts would hide the gaps but not
// the seams). A block's neighbour across an edge has its level or the next coarser one (the ring
// structure). The coarser block's edge vertices are the finer block's even edge vertices (same
// sample points, same stored heights: the tiles nest), so the finer block collapses each odd
// edge vertex onto its even neighbour towards the edge's start (north-west): its edge then
// consists of exactly the coarser block's vertices, bit for bit, and the triangles beside the
// collapsed vertex degenerate. Each vertex carries that collapsed position and the edge it lies
// on; the renderer passes, per draw, which edges abut a coarser block (ringoCoarserEdges: it
// depends only on the block's place in the matrix, so buffers never change when the matrix
// moves) and the vertex shader picks the position; ringoVertexEcef is its CPU twin.
//
// Across a change of depth the new matrix's vertices morph from the surface the old matrix drew
// (ringo_morph.hpp): each vertex carries its morph delta, and a collapsed one its target's.
#include <cstdint>
#include <span>
#include <vector>

#include <glm/ext/vector_int3.hpp>
#include <glm/vec3.hpp>

#include "tellus/core/aabb.hpp"
#include "tellus/dem/geoid.hpp"
#include "tellus/lod/ringo/ringo_block_matrix.hpp"
#include "tellus/lod/ringo/ringo_morph.hpp"

namespace tellus {

// Block edges, as bits of RingoVertex::edges and of the coarser-edge mask.
enum RingoEdge : std::uint32_t { kRingoNorth = 1, kRingoEast = 2, kRingoSouth = 4, kRingoWest = 8 };

struct RingoVertex {                 // 68 bytes, as the vertex buffer holds it
  glm::ivec3 whole{0};               // ECEF, whole metres (floor)
  glm::vec3 fraction{0.0f};          // ECEF minus whole, in [0, 1) metres
  glm::ivec3 collapsedWhole{0};      // where it goes when an edge of `edges` abuts a coarser
  glm::vec3 collapsedFraction{0.0f};  // block (odd edge vertices; the others: themselves)
  std::uint32_t normal = 0;          // unit ECEF normal, GL_INT_2_10_10_10_REV
  float heightM = 0.0f;              // above the geoid (the tint)
  std::uint32_t edges = 0;           // the edges whose coarser neighbour moves it
  // Metres along the ellipsoid normal from here to the surface the matrix morphs from
  // (RingoMorphSource), and the same at the collapsed position; drawn times the remaining morph.
  float morphDeltaM = 0.0f;
  float collapsedMorphDeltaM = 0.0f;
};
static_assert(sizeof(RingoVertex) == 68);

struct RingoBlockMesh {
  int cells = 0;  // cells a side: (cells + 1)^2 vertices, row-major, row 0 north
  std::vector<RingoVertex> vertices;
  Aabb bounds;    // ECEF, of every position (morphed or not): culling
  std::vector<float> morphDeltasM;  // each vertex's morphDeltaM, or empty: no morph source
};

// The mesh of `block` from its heights ((cells + 1)^2 samples, as loadRingoBlock gives them),
// morphing from `morphFrom`'s surface where it has one (null: no morph).
RingoBlockMesh buildRingoBlockMesh(const RingoBlock& block, int cells,
                                   std::span<const float> heights, const Geoid* geoid,
                                   const RingoMorphSource* morphFrom = nullptr);

// The edges of the block at offset (dx, dy) from the centre (east, south positive) whose
// neighbour in the matrix is coarser.
std::uint32_t ringoCoarserEdges(int dx, int dy, const RingoLayout& layout);

// Where vertex `v` is drawn (ECEF) when `coarserEdges` abut coarser blocks, `morphRemaining`
// (0 .. 1) of its morph delta still to go: the vertex shader's choice.
glm::dvec3 ringoVertexEcef(const RingoVertex& v, std::uint32_t coarserEdges,
                           float morphRemaining = 0.0f);

// The unit ECEF normal packed in a vertex.
glm::vec3 unpackRingoNormal(std::uint32_t packed);

}  // namespace tellus
