#include "tellus/lod/rag/rag_mesh.hpp"

#include <algorithm>
#include <cmath>

namespace tellus::rag {

float sampleNearest(const HeightGrid& grid, float u, float v) {
  // floor(x + 0.5) as the shader computes it; clamped like texelFetch with clamped coordinates.
  const int col = std::clamp(int(std::floor(u + 0.5f)), 0, grid.width - 1);
  const int rowFromSouth = std::clamp(int(std::floor(v + 0.5f)), 0, grid.height - 1);
  return grid.at(col, grid.height - 1 - rowFromSouth);
}

Result<std::vector<Triangle>> buildCoarseMesh(const HeightGrid& grid, int vertices) {
  if (vertices < kMinCoarseVertices || vertices > kMaxCoarseVertices) {
    return makeError("RAG coarse mesh: {} vertices a side is outside {} to {}", vertices,
                     kMinCoarseVertices, kMaxCoarseVertices);
  }
  if (grid.width < 2 || grid.height < 2) {
    return makeError("RAG coarse mesh: the height map needs at least 2 x 2 samples");
  }
  const int cells = vertices - 1;
  const auto vertexAt = [&](int i, int j) {
    const float u = float(double(i) * double(grid.width - 1) / double(cells));
    const float v = float(double(j) * double(grid.height - 1) / double(cells));
    return Vertex(u, v, sampleNearest(grid, u, v));
  };
  std::vector<Triangle> mesh;
  mesh.reserve(std::size_t(cells) * std::size_t(cells) * 2);
  for (int j = 0; j < cells; ++j) {
    for (int i = 0; i < cells; ++i) {
      const Vertex sw = vertexAt(i, j), se = vertexAt(i + 1, j);
      const Vertex nw = vertexAt(i, j + 1), ne = vertexAt(i + 1, j + 1);
      if ((i + j) % 2 == 0) {  // diagonal south-west to north-east
        mesh.push_back({{se, ne, sw}});
        mesh.push_back({{nw, sw, ne}});
      } else {  // diagonal south-east to north-west
        mesh.push_back({{sw, se, nw}});
        mesh.push_back({{ne, nw, se}});
      }
    }
  }
  return mesh;
}

}  // namespace tellus::rag
