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

namespace {

Status checkCoarseRequest(const HeightGrid& grid, int vertices) {
  if (vertices < kMinCoarseVertices || vertices > kMaxCoarseVertices) {
    return makeError("RAG coarse mesh: {} vertices a side is outside {} to {}", vertices,
                     kMinCoarseVertices, kMaxCoarseVertices);
  }
  if (grid.width < 2 || grid.height < 2) {
    return makeError("RAG coarse mesh: the height map needs at least 2 x 2 samples");
  }
  return {};
}

// cellsX x cellsY cells whose corner (i, j) is vertexAt(i, j), two right triangles a cell with
// the diagonal alternating like a checkerboard.
template <typename VertexAt>
std::vector<Triangle> gridOfRightTriangles(int cellsX, int cellsY, VertexAt&& vertexAt) {
  std::vector<Triangle> mesh;
  mesh.reserve(std::size_t(cellsX) * std::size_t(cellsY) * 2);
  for (int j = 0; j < cellsY; ++j) {
    for (int i = 0; i < cellsX; ++i) {
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

}  // namespace

Result<std::vector<Triangle>> buildCoarseMesh(const HeightGrid& grid, int vertices) {
  if (Status ok = checkCoarseRequest(grid, vertices); !ok) return ok.error();
  const int cells = vertices - 1;
  return gridOfRightTriangles(cells, cells, [&](int i, int j) {
    const float u = float(double(i) * double(grid.width - 1) / double(cells));
    const float v = float(double(j) * double(grid.height - 1) / double(cells));
    return Vertex(u, v, sampleNearest(grid, u, v));
  });
}

int alignedCellSamples(const HeightGrid& grid, int vertices) {
  const double wanted =
      double(std::max(grid.width, grid.height) - 1) / double(std::max(1, vertices - 1));
  int cell = 1;
  while (cell * 2 <= wanted * std::sqrt(2.0)) cell *= 2;  // nearest in log scale
  return cell;
}

Result<std::vector<Triangle>> buildAlignedCoarseMesh(const HeightGrid& grid, int vertices) {
  if (Status ok = checkCoarseRequest(grid, vertices); !ok) return ok.error();
  const int cell = alignedCellSamples(grid, vertices);
  const int cellsX = (grid.width - 2) / cell + 1, cellsY = (grid.height - 2) / cell + 1;
  return gridOfRightTriangles(cellsX, cellsY, [&](int i, int j) {
    const float u = float(std::min(i * cell, grid.width - 1));
    const float v = float(std::min(j * cell, grid.height - 1));
    return Vertex(u, v, sampleNearest(grid, u, v));
  });
}

}  // namespace tellus::rag
