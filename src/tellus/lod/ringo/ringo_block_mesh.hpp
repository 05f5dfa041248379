#pragma once
// RINGO (seed 002): a block's static mesh, what its GPU buffer holds. GL-free; the CPU reference
// of the renderer's vertex shader.
//
// Positions are ECEF relative to the block's own centre (floats stay exact to about a
// millimetre in a 20 km block), so per frame the renderer only hands each block the offset of
// its centre from the eye, formed in double on the CPU. Heights are the store's (above the
// geoid); with a geoid the vertex sits at the ellipsoidal height H + N.
//
// Crack-free joins between rings (the seed is silent on them; skirts would hide the gaps but not
// the T-junction seams). A block's neighbour across an edge has its level or the next coarser
// one (the ring structure). A coarser neighbour's edge vertices are the finer block's even edge
// vertices (same sample points, same stored heights: the tiles nest), so the finer block moves
// each odd edge vertex to the midpoint of its two even neighbours: both blocks then draw the
// same polyline along the edge. Each vertex carries that snapped position and the edges it lies
// on; the renderer passes, per draw, which edges abut a coarser block (ringoCoarserEdges) and
// the vertex shader picks the position (ringoVertexPosition is its CPU twin). The mask depends
// only on the block's place in the matrix, so the buffers never change when the matrix moves.
#include <cstdint>
#include <span>
#include <vector>

#include <glm/vec3.hpp>

#include "tellus/dem/geoid.hpp"
#include "tellus/lod/ringo/ringo_block_matrix.hpp"

namespace tellus {

// Block edges, as bits of RingoVertex::edges and of the coarser-edge mask.
enum RingoEdge : std::uint32_t { kRingoNorth = 1, kRingoEast = 2, kRingoSouth = 4, kRingoWest = 8 };

struct RingoVertex {         // 36 bytes, as the vertex buffer holds it
  glm::vec3 position{0.0f};  // ECEF relative to the block's centre, metres
  glm::vec3 snapped{0.0f};   // where it goes when an edge of `edges` abuts a coarser block
  std::uint32_t normal = 0;  // unit ECEF normal, GL_INT_2_10_10_10_REV
  float heightM = 0.0f;      // above the geoid (the tint)
  std::uint32_t edges = 0;   // the edges whose coarser neighbour moves it (odd edge vertices)
};
static_assert(sizeof(RingoVertex) == 36);

struct RingoBlockMesh {
  glm::dvec3 centreEcef{0.0};  // the origin of the positions
  int cells = 0;               // cells a side: (cells + 1)^2 vertices, row-major, row 0 north
  std::vector<RingoVertex> vertices;
};

// The mesh of `block` from its heights ((cells + 1)^2 samples, as loadRingoBlock gives them).
RingoBlockMesh buildRingoBlockMesh(const RingoBlock& block, int cells,
                                   std::span<const float> heights, const Geoid* geoid);

// The edges of the block at offset (dx, dy) from the centre (east, south positive) whose
// neighbour in the matrix is coarser.
std::uint32_t ringoCoarserEdges(int dx, int dy, const RingoLayout& layout);

// Where vertex `v` is drawn (relative to its block's centre) when `coarserEdges` abut coarser
// blocks: the vertex shader's choice.
glm::vec3 ringoVertexPosition(const RingoVertex& v, std::uint32_t coarserEdges);

// The unit ECEF normal packed in a vertex.
glm::vec3 unpackRingoNormal(std::uint32_t packed);

}  // namespace tellus
