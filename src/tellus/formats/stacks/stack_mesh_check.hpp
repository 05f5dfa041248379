#pragma once
// Checks on a quadrangulated stack mesh (quadrangulation.hpp), for tests and `tellus stacks
// quad`: vertices welded where neighbouring nodes duplicate them, whether the surface is closed
// and consistently oriented, and its Euler characteristic (2 for a solid without tunnels, 0 with
// one arch...). GL-free.
#include <cstdint>
#include <vector>

#include "tellus/formats/stacks/quadrangulation.hpp"

namespace tellus {

struct StackMeshCheck {
  std::size_t vertices = 0;       // after welding equal positions
  std::size_t quads = 0;
  std::size_t degenerateQuads = 0;  // a welded vertex twice in one quad
  std::size_t edges = 0;            // undirected, after welding
  // Directed edges a -> b used more often than b -> a: holes (an edge with one face) or a
  // flipped face; 0 when the surface is closed and consistently oriented.
  std::size_t unbalancedEdges = 0;
  std::size_t nonManifoldEdges = 0;  // edges of more than two quads (balanced, but pinched)
  long long eulerCharacteristic() const {
    return static_cast<long long>(vertices) - static_cast<long long>(edges) + static_cast<long long>(quads);
  }
  bool watertight() const { return unbalancedEdges == 0; }
};

// The quads are read back from the triangle pairs (v0 v1 v2, v0 v2 v3) the pipeline writes.
StackMeshCheck checkStackMesh(const StackMesh& mesh);

}  // namespace tellus
