#pragma once
// Topology checks of a RAG mesh (a triangle soup as the transform feedback buffer holds it),
// for the tests and the crack proof in docs/rag.md. RAG only ever inserts vertices at edge
// midpoints, (a + b) * 0.5 in float, so a vertex in the interior of an edge (a T-vertex) of a
// RAG mesh is always at that edge's midpoint: checking the midpoint of every edge finds them
// all.
#include <cstdint>
#include <vector>

#include "tellus/lod/rag/rag_mesh.hpp"

namespace tellus::rag {

struct MeshCheck {
  std::uint64_t triangles = 0;
  std::uint64_t edges = 0;  // triangle edges checked (3 per triangle)
  // Edges with another triangle's vertex at their midpoint.
  std::uint64_t tVertices = 0;
  // Of those, the ones whose vertex is not at the edge's interpolated height: a crack the
  // width of `largestGapM`.
  std::uint64_t visibleTVertices = 0;
  float largestGapM = 0.0f;
  // Positions (u, v) where triangles disagree on the height of a shared vertex.
  std::uint64_t heightConflicts = 0;
};

MeshCheck checkMesh(const std::vector<Triangle>& mesh);

}  // namespace tellus::rag
