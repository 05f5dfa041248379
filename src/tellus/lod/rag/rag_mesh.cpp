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

float sampleSurface(const HeightGrid& grid, float u, float v) {
  if (grid.width < 2 || grid.height < 2) return sampleNearest(grid, u, v);
  const float col = std::clamp(u, 0.0f, float(grid.width - 1));
  const float rowFromSouth = std::clamp(v, 0.0f, float(grid.height - 1));
  const int c0 = std::min(int(std::floor(col)), grid.width - 2);
  const int s0 = std::min(int(std::floor(rowFromSouth)), grid.height - 2);
  const float fx = col - float(c0), fy = rowFromSouth - float(s0);  // fy grows northwards
  const int north = grid.height - 2 - s0, south = grid.height - 1 - s0;  // rows, 0 north
  const float sw = grid.at(c0, south), se = grid.at(c0 + 1, south);
  const float nw = grid.at(c0, north), ne = grid.at(c0 + 1, north);
  if (fy <= fx) return sw + (se - sw) * fx + (ne - se) * fy;  // south-east of the diagonal
  return sw + (nw - sw) * fy + (ne - nw) * fx;
}

float sampleMap(const HeightGrid& grid, float u, float v, MapSampling sampling) {
  return sampling == MapSampling::Surface ? sampleSurface(grid, u, v)
                                          : sampleNearest(grid, u, v);
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

enum class Diagonals {
  Alternating,          // like a checkerboard: a 4-8 mesh (the seed's)
  SouthWestNorthEast,   // all alike, as the reference's cells (HeightGrid::meshHeightAtWorld)
};

// cellsX x cellsY cells whose corner (i, j) is vertexAt(i, j), two right triangles a cell.
template <typename VertexAt>
std::vector<Triangle> gridOfRightTriangles(int cellsX, int cellsY, Diagonals diagonals,
                                           VertexAt&& vertexAt) {
  std::vector<Triangle> mesh;
  mesh.reserve(std::size_t(cellsX) * std::size_t(cellsY) * 2);
  for (int j = 0; j < cellsY; ++j) {
    for (int i = 0; i < cellsX; ++i) {
      const Vertex sw = vertexAt(i, j), se = vertexAt(i + 1, j);
      const Vertex nw = vertexAt(i, j + 1), ne = vertexAt(i + 1, j + 1);
      if (diagonals == Diagonals::SouthWestNorthEast || (i + j) % 2 == 0) {
        // diagonal south-west to north-east
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
  return gridOfRightTriangles(cells, cells, Diagonals::Alternating, [&](int i, int j) {
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
  return gridOfRightTriangles(cellsX, cellsY, Diagonals::SouthWestNorthEast, [&](int i, int j) {
    const float u = float(std::min(i * cell, grid.width - 1));
    const float v = float(std::min(j * cell, grid.height - 1));
    return Vertex(u, v, sampleNearest(grid, u, v));
  });
}

}  // namespace tellus::rag
