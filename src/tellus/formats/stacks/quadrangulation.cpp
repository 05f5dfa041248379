#include "tellus/core/stopwatch.hpp"
#include "tellus/formats/stacks/quadrangulation.hpp"

#include <algorithm>
#include <bit>
#include <chrono>
#include <cmath>
#include <mutex>

#include <tbb/parallel_for.h>

#include "tellus/formats/stacks/dual_contouring.hpp"

namespace tellus {
namespace {

// The coverage of cell `cell` (units [cell * kSubCell, (cell + 1) * kSubCell)) by a layer: the
// seed's rules in integers (first cell 1 - frac(s), last frac(e), those between 1, a layer in
// one cell e - s) are all this one overlap.
std::uint32_t coverage(const QuantisedLayer& layer, std::int32_t cell) {
  const std::int32_t low = std::max(layer.bottom, cell * kSubCell);
  const std::int32_t high = std::min(layer.top, (cell + 1) * kSubCell);
  return high > low ? std::uint32_t(high - low) : 0u;
}

// Floor division by kSubCell (layers may, in principle, start below the base).
std::int32_t cellOf(std::int32_t units) {
  return units >= 0 ? units / kSubCell : -((-units + kSubCell - 1) / kSubCell);
}

std::uint32_t total(const DensitySample& s) {
  return s[0] + s[1] + s[2] + s[3];
}

}  // namespace

Status QuadParams::check() const {
  if (nodeCells < 3 || nodeCells > 64) {
    return makeError("node size must be 3 to 64 cells (got {})", nodeCells);
  }
  if (filterRadius < 0 || filterRadius > 4) {
    return makeError("smoothing radius must be 0 to 4 cells (got {})", filterRadius);
  }
  return {};
}

std::vector<std::uint32_t> QuadParams::filterTaps() const {
  const int taps = 2 * filterRadius + 1;
  std::vector<std::uint32_t> weights(std::size_t(taps), 1u);
  if (filter == SmoothingFilter::Gauss) {
    // Row 2r of Pascal's triangle.
    for (int row = 1; row < taps; ++row) {
      for (int k = row - 1; k >= 1; --k) weights[std::size_t(k)] += weights[std::size_t(k - 1)];
    }
  }
  return weights;
}

std::uint32_t QuadParams::filterNorm() const {
  std::uint32_t sum = 0;
  for (std::uint32_t w : filterTaps()) sum += w;
  return sum * sum * sum;
}

QuadStageTimes& QuadStageTimes::operator+=(const QuadStageTimes& o) {
  density += o.density;
  smooth += o.smooth;
  classify += o.classify;
  allocate += o.allocate;
  attributes += o.attributes;
  faces += o.faces;
  return *this;
}

NodeGrid NodeGrid::of(const QuantisedStacks& stacks, const QuadParams& params) {
  const int stride = params.nodeCells - 1;
  // Cells -1 .. size must be covered (the margin of air on both sides), and the last node's
  // last cell is left to a next node that does not exist, so: ceil((size + 1) / stride).
  const auto nodes = [&](int size) { return (size + 1 + stride - 1) / stride; };
  NodeGrid grid;
  grid.nodesX = nodes(stacks.width);
  grid.nodesY = nodes(stacks.height);
  grid.nodesZ = nodes(stacks.cellsZ);
  grid.nodeCells = params.nodeCells;
  return grid;
}

std::array<int, 3> NodeGrid::origin(NodeKey key) const {
  const int stride = nodeCells - 1;
  return {-1 + key.x * stride, -1 + key.y * stride, -1 + key.z * stride};
}

bool nodeMayHaveSurface(const QuantisedStacks& stacks, const QuadParams& params, NodeKey key,
                        const NodeGrid& grid) {
  const std::array<int, 3> origin = grid.origin(key);
  const int reach = 1 + params.filterRadius;
  const int first = -reach, last = params.nodeCells + reach;  // raw samples, node-local
  const std::int32_t low = (origin[2] + first) * kSubCell;
  const std::int32_t high = (origin[2] + last + 1) * kSubCell;
  bool anyAir = false, anySolid = false;
  for (int y = origin[1] + first; y <= origin[1] + last; ++y) {
    for (int x = origin[0] + first; x <= origin[0] + last; ++x) {
      // How much of [low, high) the column's layers cover.
      std::int64_t covered = 0;
      for (const QuantisedLayer& layer : stacks.column(x, y)) {
        covered += std::max(0, std::min(layer.top, high) - std::max(layer.bottom, low));
      }
      if (covered == 0) anyAir = true;
      else if (covered == high - low) anySolid = true;
      else return true;  // a boundary inside the range
      if (anyAir && anySolid) return true;
    }
  }
  return false;
}

std::vector<NodeKey> nodesWithSurface(const QuantisedStacks& stacks, const QuadParams& params) {
  const NodeGrid grid = NodeGrid::of(stacks, params);
  std::vector<std::vector<NodeKey>> perSlab(std::size_t(grid.nodesZ));
  tbb::parallel_for(0, grid.nodesZ, [&](int z) {
    for (int y = 0; y < grid.nodesY; ++y) {
      for (int x = 0; x < grid.nodesX; ++x) {
        if (nodeMayHaveSurface(stacks, params, {x, y, z}, grid)) {
          perSlab[std::size_t(z)].push_back({x, y, z});
        }
      }
    }
  });
  std::vector<NodeKey> nodes;
  for (const auto& slab : perSlab) nodes.insert(nodes.end(), slab.begin(), slab.end());
  return nodes;
}

DensityVolume densityStage(const QuantisedStacks& stacks, const QuadParams& params,
                           std::array<int, 3> origin) {
  const int side = params.rawSide();
  const int shift = 1 + params.filterRadius;  // raw sample 0 is node-local -shift
  DensityVolume raw{side, side, side,
                    std::vector<DensitySample>(std::size_t(side) * side * side, DensitySample{})};
  for (int v = 0; v < side; ++v) {
    for (int u = 0; u < side; ++u) {
      // One stack, one column of cells (the seed's per-stack thread).
      const auto layers = stacks.column(origin[0] - shift + u, origin[1] - shift + v);
      const std::int32_t z0 = origin[2] - shift;
      for (const QuantisedLayer& layer : layers) {
        const std::int32_t first = std::max(cellOf(layer.bottom), z0);
        const std::int32_t last = std::min(cellOf(layer.top - 1), z0 + side - 1);
        for (std::int32_t cell = first; cell <= last; ++cell) {
          raw.samples[raw.index(u, v, cell - z0)][layer.channel] += coverage(layer, cell);
        }
      }
    }
  }
  return raw;
}

DensityVolume smoothStage(const DensityVolume& raw, const QuadParams& params) {
  const std::vector<std::uint32_t> taps = params.filterTaps();
  const int r = params.filterRadius;
  DensityVolume in = raw;
  for (int axis = 0; axis < 3; ++axis) {
    // Each pass shrinks its axis by 2r (the samples the filter needs on each side).
    DensityVolume out{in.sizeX - (axis == 0 ? 2 * r : 0), in.sizeY - (axis == 1 ? 2 * r : 0),
                      in.sizeZ - (axis == 2 ? 2 * r : 0), {}};
    out.samples.assign(std::size_t(out.sizeX) * out.sizeY * out.sizeZ, DensitySample{});
    for (int z = 0; z < out.sizeZ; ++z) {
      for (int y = 0; y < out.sizeY; ++y) {
        for (int x = 0; x < out.sizeX; ++x) {
          DensitySample sum{};
          for (int t = 0; t <= 2 * r; ++t) {
            const DensitySample& s = in.samples[in.index(x + (axis == 0 ? t : 0),
                                                         y + (axis == 1 ? t : 0),
                                                         z + (axis == 2 ? t : 0))];
            for (int c = 0; c < kMaterialChannels; ++c) sum[c] += taps[std::size_t(t)] * s[c];
          }
          out.samples[out.index(x, y, z)] = sum;
        }
      }
    }
    in = std::move(out);
  }
  return in;
}

unsigned cellClassification(const DensityVolume& smoothed, int i, int j, int k,
                            std::uint32_t isoTwice) {
  unsigned classification = 0;
  for (int c = 0; c < 8; ++c) {
    // Cell corner (i, j, k) is smoothed sample (i + 1, j + 1, k + 1): sample 0 is -1.
    const DensitySample& s = smoothed.samples[smoothed.index(
        i + 1 + (c & 1), j + 1 + ((c >> 1) & 1), k + 1 + ((c >> 2) & 1))];
    if (2u * total(s) > isoTwice) classification |= 1u << c;
  }
  return classification;
}

std::vector<CellEntry> classifyStage(const DensityVolume& smoothed, const QuadParams& params) {
  const int n = params.nodeCells;
  std::vector<CellEntry> cells(std::size_t(n) * n * n);
  for (int k = 0; k < n; ++k) {
    for (int j = 0; j < n; ++j) {
      for (int i = 0; i < n; ++i) {
        const unsigned classification = cellClassification(smoothed, i, j, k, params.isoTwice());
        cells[std::size_t(i) + std::size_t(n) * (std::size_t(j) + std::size_t(n) * k)].code =
            dc::cellCode(classification, dc::ownedQuads(classification, i, j, k, n),
                         dc::cellHasVertex(classification));
      }
    }
  }
  return cells;
}

void allocateStage(std::vector<CellEntry>& cells, const QuadParams& params,
                   QuadCounters& counters) {
  const int n = params.nodeCells;
  for (int row = 0; row < n * n; ++row) {
    CellEntry* rowCells = cells.data() + std::size_t(row) * std::size_t(n);
    std::uint32_t vertices = 0, quads = 0;
    for (int i = 0; i < n; ++i) {
      const std::uint32_t code = rowCells[i].code;
      if (dc::codeHasVertex(code)) ++vertices;
      quads += std::uint32_t(std::popcount(dc::codeQuads(code)));
    }
    // The GPU's atomicAdd on the counters; rows in order here.
    std::uint32_t vertex = counters.vertexCount;
    counters.vertexCount += vertices;
    std::uint32_t offset = counters.indexCount;
    counters.indexCount += 6u * quads;
    for (int i = 0; i < n; ++i) {
      CellEntry& cell = rowCells[i];
      if (dc::codeHasVertex(cell.code)) cell.vertexIndex = vertex++;
      cell.indexOffset = offset;
      offset += 6u * std::uint32_t(std::popcount(dc::codeQuads(cell.code)));
    }
  }
}

namespace {

// The cell-local position of cell (i, j, k)'s vertex (a cell with a vertex): the mean of its
// edge crossings (Marching Cubes' vertices), each corner 0..1.
std::array<float, 3> cellCrossingMean(const DensityVolume& smoothed, int i, int j, int k,
                                      std::uint32_t isoTwice) {
  const float iso = float(isoTwice / 2u);
  std::array<std::int32_t, 8> corner{};
  unsigned classification = 0;
  for (int c = 0; c < 8; ++c) {
    corner[std::size_t(c)] = std::int32_t(total(smoothed.samples[smoothed.index(
        i + 1 + (c & 1), j + 1 + ((c >> 1) & 1), k + 1 + ((c >> 2) & 1))]));
    if (2u * std::uint32_t(corner[std::size_t(c)]) > isoTwice) classification |= 1u << c;
  }
  float px = 0.0f, py = 0.0f, pz = 0.0f;
  int crossings = 0;
  for (const auto& edge : dc::kCellEdges) {
    const int a = edge[0], b = edge[1];
    if (dc::cornerInside(classification, a) == dc::cornerInside(classification, b)) continue;
    const float da = float(corner[std::size_t(a)]), db = float(corner[std::size_t(b)]);
    const float t = (iso - da) / (db - da);
    const float ax = float(a & 1), ay = float((a >> 1) & 1), az = float((a >> 2) & 1);
    px += ax + t * (float(b & 1) - ax);
    py += ay + t * (float((b >> 1) & 1) - ay);
    pz += az + t * (float((b >> 2) & 1) - az);
    ++crossings;
  }
  const float count = float(crossings);
  return {px / count, py / count, pz / count};
}

// Cell-local position to world metres (the volume's cell (0, 0, 0) is sample `origin`).
std::array<float, 3> placeInWorld(std::array<float, 3> local, int i, int j, int k,
                                  const QuantisedStacks& stacks, std::array<int, 3> origin) {
  return {(float(origin[0] + i) + local[0]) * float(stacks.spacingM),
          (float(origin[1] + j) + local[1]) * float(stacks.spacingM),
          float(stacks.baseM) + (float(origin[2] + k) + local[2] + 0.5f) * float(stacks.cellM)};
}

}  // namespace

std::array<float, 3> cellVertexPosition(const DensityVolume& smoothed, int i, int j, int k,
                                        const QuantisedStacks& stacks, std::uint32_t isoTwice,
                                        std::array<int, 3> origin) {
  return placeInWorld(cellCrossingMean(smoothed, i, j, k, isoTwice), i, j, k, stacks, origin);
}

StackVertex cellVertex(const DensityVolume& smoothed, int i, int j, int k,
                       const QuantisedStacks& stacks, std::uint32_t isoTwice,
                       std::array<int, 3> origin) {
  const auto sample = [&](int x, int y, int z) -> const DensitySample& {
    return smoothed.samples[smoothed.index(x + 1, y + 1, z + 1)];  // node-local, from -1
  };
  const auto density = [&](int x, int y, int z) { return std::int32_t(total(sample(x, y, z))); };
  // Position: the mean of the edge crossings (Marching Cubes' vertices), cell-local.
  const auto [px, py, pz] = cellCrossingMean(smoothed, i, j, k, isoTwice);
  // Normal: the 3D Sobel gradient at the 8 corners, interpolated at the vertex.
  float gx = 0.0f, gy = 0.0f, gz = 0.0f;
  for (int c = 0; c < 8; ++c) {
    const int x = i + (c & 1), y = j + ((c >> 1) & 1), z = k + ((c >> 2) & 1);
    std::int32_t sx = 0, sy = 0, sz = 0;
    for (int e = -1; e <= 1; ++e) {
      for (int f = -1; f <= 1; ++f) {
        const std::int32_t w = (2 - std::abs(e)) * (2 - std::abs(f));
        sx += w * (density(x + 1, y + e, z + f) - density(x - 1, y + e, z + f));
        sy += w * (density(x + e, y + 1, z + f) - density(x + e, y - 1, z + f));
        sz += w * (density(x + e, y + f, z + 1) - density(x + e, y + f, z - 1));
      }
    }
    const float wx = (c & 1) ? px : 1.0f - px;
    const float wy = ((c >> 1) & 1) ? py : 1.0f - py;
    const float wz = ((c >> 2) & 1) ? pz : 1.0f - pz;
    const float weight = wx * wy * wz;
    gx += weight * float(sx);
    gy += weight * float(sy);
    gz += weight * float(sz);
  }
  // Density grows into the solid: the outward normal is minus the gradient in metres.
  gx = gx / float(stacks.spacingM);
  gy = gy / float(stacks.spacingM);
  gz = gz / float(stacks.cellM);
  const float length = std::sqrt(gx * gx + gy * gy + gz * gz);
  // Materials: each channel's smoothed density at the corners, weighted by the air the corner
  // holds (isoTwice - total: the thin top layer of grass shows, not the rock under it, which
  // fills the inside corners), normalised; the plain sums where every corner is full or empty.
  std::array<float, kMaterialChannels> channel{};
  std::array<std::uint32_t, kMaterialChannels> plain{};
  for (int c = 0; c < 8; ++c) {
    const DensitySample& s = sample(i + (c & 1), j + ((c >> 1) & 1), k + ((c >> 2) & 1));
    const float air = float(isoTwice - total(s));
    for (int m = 0; m < kMaterialChannels; ++m) {
      channel[std::size_t(m)] += float(s[std::size_t(m)]) * air;
      plain[std::size_t(m)] += s[std::size_t(m)];
    }
  }
  float sum = channel[0] + channel[1] + channel[2] + channel[3];
  if (!(sum > 0.0f)) {
    for (int m = 0; m < kMaterialChannels; ++m) channel[std::size_t(m)] = float(plain[std::size_t(m)]);
    sum = channel[0] + channel[1] + channel[2] + channel[3];
  }
  StackVertex v;
  const std::array<float, 3> world = placeInWorld({px, py, pz}, i, j, k, stacks, origin);
  v.position = {world[0], world[1], world[2], float(stacks.level)};
  v.normal = length > 0.0f ? std::array<float, 4>{-gx / length, -gy / length, -gz / length, 0.0f}
                           : std::array<float, 4>{0.0f, 0.0f, 1.0f, 0.0f};
  for (int m = 0; m < kMaterialChannels; ++m) {
    v.materials[std::size_t(m)] = channel[std::size_t(m)] / sum;
  }
  return v;
}

void attributesStage(const DensityVolume& smoothed, const std::vector<CellEntry>& cells,
                     const QuantisedStacks& stacks, const QuadParams& params,
                     std::array<int, 3> origin, std::vector<StackVertex>& vertices) {
  const int n = params.nodeCells;
  for (int k = 0; k < n; ++k) {
    for (int j = 0; j < n; ++j) {
      for (int i = 0; i < n; ++i) {
        const CellEntry& cell =
            cells[std::size_t(i) + std::size_t(n) * (std::size_t(j) + std::size_t(n) * k)];
        if (!dc::codeHasVertex(cell.code)) continue;
        vertices[cell.vertexIndex] =
            cellVertex(smoothed, i, j, k, stacks, params.isoTwice(), origin);
      }
    }
  }
}

void facesStage(const std::vector<CellEntry>& cells, const QuadParams& params,
                std::vector<std::uint32_t>& indices) {
  const int n = params.nodeCells;
  const auto at = [&](int i, int j, int k) -> const CellEntry& {
    return cells[std::size_t(i) + std::size_t(n) * (std::size_t(j) + std::size_t(n) * k)];
  };
  for (int k = 0; k < n; ++k) {
    for (int j = 0; j < n; ++j) {
      for (int i = 0; i < n; ++i) {
        const CellEntry& cell = at(i, j, k);
        const unsigned quads = dc::codeQuads(cell.code);
        std::uint32_t offset = cell.indexOffset;
        for (int axis = 0; axis < 3; ++axis) {
          if (!((quads >> axis) & 1u)) continue;
          std::array<std::uint32_t, 4> v{};
          for (int q = 0; q < 4; ++q) {
            const auto& d = dc::kQuadCells[std::size_t(axis)][std::size_t(q)];
            v[std::size_t(q)] = at(i + d[0], j + d[1], k + d[2]).vertexIndex;
          }
          // Corner 0 inside: the surface faces +axis and the listed order is counter-clockwise.
          if (!dc::cornerInside(cell.code, 0)) std::swap(v[1], v[3]);
          const std::array<std::uint32_t, 6> triangles{v[0], v[1], v[2], v[0], v[2], v[3]};
          std::copy(triangles.begin(), triangles.end(), indices.begin() + offset);
          offset += 6;
        }
      }
    }
  }
}

void quadrangulateNode(const QuantisedStacks& stacks, const QuadParams& params,
                       std::array<int, 3> origin, StackMesh& mesh, std::vector<CellEntry>* cellsOut,
                       QuadStageTimes* times) {
  QuadStageTimes t;
  Stopwatch stage;
  const DensityVolume raw = densityStage(stacks, params, origin);
  t.density = stage.lapMs();
  const DensityVolume smoothed = smoothStage(raw, params);
  t.smooth = stage.lapMs();
  std::vector<CellEntry> cells = classifyStage(smoothed, params);
  t.classify = stage.lapMs();
  QuadCounters counters;
  counters.vertexCount = std::uint32_t(mesh.vertices.size());
  counters.indexCount = std::uint32_t(mesh.indices.size());
  allocateStage(cells, params, counters);
  mesh.vertices.resize(counters.vertexCount);
  mesh.indices.resize(counters.indexCount);
  t.allocate = stage.lapMs();
  attributesStage(smoothed, cells, stacks, params, origin, mesh.vertices);
  t.attributes = stage.lapMs();
  facesStage(cells, params, mesh.indices);
  t.faces = stage.lapMs();
  if (cellsOut) *cellsOut = std::move(cells);
  if (times) *times += t;
}

StackMesh quadrangulateNodes(const QuantisedStacks& stacks, const QuadParams& params,
                             const std::vector<NodeKey>& nodes, QuadStageTimes* times) {
  const NodeGrid grid = NodeGrid::of(stacks, params);
  std::vector<StackMesh> meshes(nodes.size());
  std::mutex timesMutex;
  tbb::parallel_for(std::size_t(0), nodes.size(), [&](std::size_t n) {
    QuadStageTimes t;
    quadrangulateNode(stacks, params, grid.origin(nodes[n]), meshes[n], nullptr, &t);
    if (times) {
      const std::lock_guard lock(timesMutex);
      *times += t;
    }
  });
  StackMesh mesh;
  std::size_t vertexCount = 0, indexCount = 0;
  for (const StackMesh& m : meshes) {
    vertexCount += m.vertices.size();
    indexCount += m.indices.size();
  }
  mesh.vertices.reserve(vertexCount);
  mesh.indices.reserve(indexCount);
  for (StackMesh& m : meshes) {
    const auto base = std::uint32_t(mesh.vertices.size());
    mesh.vertices.insert(mesh.vertices.end(), m.vertices.begin(), m.vertices.end());
    for (std::uint32_t index : m.indices) mesh.indices.push_back(base + index);
    m = StackMesh{};
  }
  return mesh;
}

}  // namespace tellus
