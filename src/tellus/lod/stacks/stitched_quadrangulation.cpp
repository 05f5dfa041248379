#include "tellus/lod/stacks/stitched_quadrangulation.hpp"

#include <algorithm>
#include <limits>

#include "tellus/formats/stacks/dual_contouring.hpp"
#include "tellus/lod/stacks/seam_blend.hpp"

namespace tellus {

StitchGeometry StitchGeometry::of(const StackOctree& octree, const OctreeKey& key,
                                  std::uint32_t mask) {
  StitchGeometry g;
  g.n = octree.nodeCells();
  g.mask = mask;
  const std::array<int, 3> node = octree.origin(key);
  const std::array<int, 3> parent = octree.origin(key.parent());
  for (int a = 0; a < 3; ++a) g.parentFirst[std::size_t(a)] = 2 * parent[std::size_t(a)] - node[std::size_t(a)];
  return g;
}

bool StitchGeometry::coarseCell(int x, int y, int z) const {
  const std::array<int, 3> c{x, y, z};
  for (std::uint32_t bits = mask; bits != 0u; bits &= bits - 1u) {
    const int bit = __builtin_ctz(bits);
    const std::array<int, 3> d{bit % 3 - 1, (bit / 3) % 3 - 1, bit / 9 - 1};
    bool inside = true;
    for (int a = 0; a < 3 && inside; ++a) {
      // The neighbour's cells, in the node's cells: 2 (n - 1) per parent step, 2n long.
      const int low = parentFirst[std::size_t(a)] + 2 * d[std::size_t(a)] * (n - 1);
      inside = c[std::size_t(a)] >= low && c[std::size_t(a)] < low + 2 * n;
    }
    if (inside) return true;
  }
  return false;
}

bool StitchGeometry::coarseSample(int x, int y, int z) const {
  if (mask == 0u) return false;
  for (int c = 0; c < 8; ++c) {
    if (coarseCell(x - (c & 1), y - ((c >> 1) & 1), z - ((c >> 2) & 1))) return true;
  }
  return false;
}

QuadParams coarseVolumeParams(const QuadParams& params) {
  QuadParams coarse = params;
  coarse.nodeCells = (params.nodeCells - 1) / 2 + 1;
  return coarse;
}

namespace {

// Floor of half (node-local samples to coarse-local: node origins are even).
int half(int v) { return v >= 0 ? v / 2 : -((-v + 1) / 2); }

// MorphTarget's position for a vertex at `own` in coarse-local cell `cell` (see the header).
std::array<float, 3> coarseMorphTarget(const DensityVolume& coarse, std::array<int, 3> cell,
                                       const QuantisedStacks& coarseStacks, std::uint32_t iso,
                                       std::array<int, 3> coarseOrigin, std::array<float, 3> own) {
  const auto vertexAt = [&](int i, int j, int k) {
    return cellVertexPosition(coarse, i, j, k, coarseStacks, iso, coarseOrigin);
  };
  const auto [ci, cj, ck] = cell;
  if (dc::cellHasVertex(cellClassification(coarse, ci, cj, ck, iso))) return vertexAt(ci, cj, ck);
  std::array<float, 3> best = own;
  float bestDistance = std::numeric_limits<float>::infinity();
  for (int dz = -1; dz <= 1; ++dz) {
    for (int dy = -1; dy <= 1; ++dy) {
      for (int dx = -1; dx <= 1; ++dx) {
        if (!dc::cellHasVertex(cellClassification(coarse, ci + dx, cj + dy, ck + dz, iso))) continue;
        const std::array<float, 3> p = vertexAt(ci + dx, cj + dy, ck + dz);
        const float ex = p[0] - own[0], ey = p[1] - own[1], ez = p[2] - own[2];
        const float distance = ex * ex + ey * ey + ez * ez;
        if (distance < bestDistance) {
          bestDistance = distance;
          best = p;
        }
      }
    }
  }
  return best;
}

}  // namespace

void quadrangulateStitchedNode(const StackOctree& octree, const OctreeKey& key,
                               std::uint32_t mask, StackMesh& mesh, std::vector<CellEntry>* cellsOut,
                               StitchStats* statsOut, std::vector<MorphTarget>* morphTargets,
                               int seamBandCells) {
  const StackLevels& levels = octree.levels();
  const QuadParams& params = levels.params();
  const int n = params.nodeCells;
  const QuantisedStacks& fine = levels.level(key.level).stacks;
  const std::array<int, 3> origin = octree.origin(key);
  const StitchGeometry geometry = StitchGeometry::of(octree, key, mask);
  StitchStats stats;

  DensityVolume smoothed = smoothStage(densityStage(fine, params, origin), params);
  const bool stitched = mask != 0u && key.level + 1 < levels.count();
  const QuadParams coarseParams = coarseVolumeParams(params);
  const std::array<int, 3> coarseOrigin{origin[0] / 2, origin[1] / 2, origin[2] / 2};
  const bool hasCoarser = key.level + 1 < levels.count();
  DensityVolume coarse;
  if (hasCoarser && (stitched || morphTargets)) {
    coarse = smoothStage(densityStage(levels.level(key.level + 1).stacks, coarseParams, coarseOrigin),
                         coarseParams);
  }
  if (stitched) {
    // Topology fitting: smoothed sample (x, y, z) is node-local sample (x - 1, y - 1, z - 1).
    for (int z = 0; z < smoothed.sizeZ; ++z) {
      for (int y = 0; y < smoothed.sizeY; ++y) {
        for (int x = 0; x < smoothed.sizeX; ++x) {
          if (!geometry.coarseSample(x - 1, y - 1, z - 1)) continue;
          smoothed.samples[smoothed.index(x, y, z)] = coarse.samples[coarse.index(
              half(x - 1) + 1, half(y - 1) + 1, half(z - 1) + 1)];
          ++stats.coarseSamples;
        }
      }
    }
  }
  const auto cellAt = [n](int i, int j, int k) {
    return std::size_t(i) + std::size_t(n) * (std::size_t(j) + std::size_t(n) * std::size_t(k));
  };
  // Classification on the fitted densities; vertices of coarse cells from the coarser level,
  // one per coarse cell (its even fine cell).
  std::vector<CellEntry> cells(std::size_t(n) * n * n);
  const std::uint32_t iso = params.isoTwice();
  for (int k = 0; k < n; ++k) {
    for (int j = 0; j < n; ++j) {
      for (int i = 0; i < n; ++i) {
        const unsigned classification = cellClassification(smoothed, i, j, k, iso);
        bool vertex = dc::cellHasVertex(classification);
        if (stitched && geometry.coarseCell(i, j, k)) {
          vertex = i % 2 == 0 && j % 2 == 0 && k % 2 == 0 &&
                   dc::cellHasVertex(cellClassification(coarse, i / 2, j / 2, k / 2, iso));
        }
        cells[cellAt(i, j, k)].code =
            dc::cellCode(classification, dc::ownedQuads(classification, i, j, k, n), vertex);
      }
    }
  }
  QuadCounters counters;
  counters.vertexCount = std::uint32_t(mesh.vertices.size());
  counters.indexCount = std::uint32_t(mesh.indices.size());
  const std::uint32_t firstVertex = counters.vertexCount;
  const std::size_t firstIndex = mesh.indices.size();
  allocateStage(cells, params, counters);
  mesh.vertices.resize(counters.vertexCount);
  mesh.indices.resize(counters.indexCount);
  if (morphTargets) morphTargets->resize(counters.vertexCount);
  const QuantisedStacks* coarseStacks = hasCoarser ? &levels.level(key.level + 1).stacks : nullptr;
  const int seamBand = std::min(seamBandCells, seamBandLimit(n));
  const std::uint32_t seam = seamBits(mask, key.x, key.y, key.z);
  for (int k = 0; k < n; ++k) {
    for (int j = 0; j < n; ++j) {
      for (int i = 0; i < n; ++i) {
        CellEntry& cell = cells[cellAt(i, j, k)];
        const bool coarseCell = stitched && geometry.coarseCell(i, j, k);
        if (!dc::codeHasVertex(cell.code)) continue;
        StackVertex& vertex = mesh.vertices[cell.vertexIndex];
        vertex = coarseCell ? cellVertex(coarse, i / 2, j / 2, k / 2, *coarseStacks, iso, coarseOrigin)
                            : cellVertex(smoothed, i, j, k, fine, iso, origin);
        if (coarseCell) ++stats.sharedVertices;
        const bool blends = seamBand > 0 && mask != 0;
        if (!morphTargets && !blends) continue;
        // The target: the vertex itself unless it can slide (see MorphTarget).
        StackVertex target = vertex;
        if (hasCoarser && !coarseCell) {
          const std::array<int, 3> cc{i / 2, j / 2, k / 2};
          if (dc::cellHasVertex(cellClassification(coarse, cc[0], cc[1], cc[2], iso))) {
            target = cellVertex(coarse, cc[0], cc[1], cc[2], *coarseStacks, iso, coarseOrigin);
          } else {
            const std::array<float, 3> at = coarseMorphTarget(
                coarse, cc, *coarseStacks, iso, coarseOrigin,
                {vertex.position[0], vertex.position[1], vertex.position[2]});
            for (std::size_t a = 0; a < 3; ++a) target.position[a] = at[a];
          }
        }
        if (blends) vertex = seamBlendedVertex(vertex, target, seamBlendWeight({i, j, k}, seam, n, seamBand));
        if (!morphTargets) continue;
        (*morphTargets)[cell.vertexIndex] = {target.position[0], target.position[1], target.position[2],
                                             packMorphTargetCell({i, j, k}, n),
                                             target.normal[0], target.normal[1], target.normal[2],
                                             packMaterials(target.materials)};
      }
    }
  }
  // T-junction removal: a coarse cell's lookups go to its even cell (which precedes it, so its
  // vertex index is set).
  for (int k = 0; k < n; ++k) {
    for (int j = 0; j < n; ++j) {
      for (int i = 0; i < n; ++i) {
        if (!stitched || !geometry.coarseCell(i, j, k)) continue;
        CellEntry& cell = cells[cellAt(i, j, k)];
        const CellEntry& even = cells[cellAt(i & ~1, j & ~1, k & ~1)];
        cell.vertexIndex = dc::codeHasVertex(even.code) ? even.vertexIndex : ~0u;
      }
    }
  }
  facesStage(cells, params, mesh.indices);
  for (std::size_t i = firstIndex; i < mesh.indices.size(); ++i) {
    if (mesh.indices[i] == ~0u) {
      ++stats.faults;
      mesh.indices[i] = firstVertex;  // keep the mesh indexable; the fault is reported
    }
  }
  if (cellsOut) *cellsOut = std::move(cells);
  if (statsOut) *statsOut = stats;
}

}  // namespace tellus
