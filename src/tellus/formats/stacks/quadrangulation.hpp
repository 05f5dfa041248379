#pragma once
// The quadrangulation pipeline of seed 003 (section 3.2), CPU reference: material stacks to an
// indexed quad mesh, one node (n^3 density cells) at a time, in the stages the compute shaders
// in shaders/stacks/ run under the same names:
//
//   density     each stack rasterised into its column of cells, per material channel
//               (coverage in 1/kSubCell of a cell; overlapping layers add up)
//   smooth      a separable box or Gauss filter, x then y then z
//   classify    each cell's 8 corners against the iso-value 1/2 and the quads it owns
//   allocate    per row of cells, the vertex and quad counts, then one atomic add each on the
//               global counters for the row's first vertex index and index-buffer offset
//   attributes  per vertex cell: position = mean of the edge crossings, normal = the
//               interpolated 3D Sobel gradient, normalised material weights (the corners'
//               channel densities weighted by the air they hold, so a surface shows its own
//               material: grass over soil over rock reads as grass)
//   faces       per cell, its quads as two triangles each from the neighbours' vertex indices
//
// Densities and everything up to the classification are integers, so the CPU and the GPU agree
// exactly on the mesh's topology; positions, normals and weights are float arithmetic written
// the same way on both sides (equal up to the GPU's division and square root rounding).
//
// Node layout: a node's cell (i, j, k), 0 <= i, j, k < n, spans samples origin + (i..i+1, ...);
// node (a, b, c) has origin -1 + (a, b, c) * (n - 1), so neighbouring nodes share one layer of
// cells and the nodes together cover the terrain with a margin of air all round (the surface is
// closed: walls at the terrain's sides and a floor under its base). GL-free.
#include <array>
#include <cstdint>
#include <vector>

#include "tellus/core/result.hpp"
#include "tellus/formats/stacks/quantised_stacks.hpp"

namespace tellus {

enum class SmoothingFilter {
  Box,    // 2r + 1 equal taps
  Gauss,  // binomial taps (1 2 1, 1 4 6 4 1, ...), a Gauss approximation in integers
};

struct QuadParams {
  int nodeCells = 17;  // n: cells per node side (the seed's 17^3)
  SmoothingFilter filter = SmoothingFilter::Gauss;
  int filterRadius = 1;  // r: 2r + 1 taps per axis (0: no smoothing)

  // nodeCells in [3, 64], filterRadius in [0, 4]; the error names the bad one.
  Status check() const;
  int smoothSide() const { return nodeCells + 3; }                  // samples -1 .. n + 1
  int rawSide() const { return nodeCells + 3 + 2 * filterRadius; }  // and the filter's reach
  std::vector<std::uint32_t> filterTaps() const;                    // 2r + 1 integer weights
  std::uint32_t filterNorm() const;  // (sum of taps)^3: smoothed = raw * filterNorm()
  // Twice the iso-value in smoothed units: a sample is inside when 2 * total > isoTwice().
  std::uint32_t isoTwice() const { return std::uint32_t(kSubCell) * filterNorm(); }
};

struct NodeKey {
  int x = 0, y = 0, z = 0;
  bool operator==(const NodeKey&) const = default;
};

// The nodes covering a terrain: node (a, b, c) with origin -1 + (a, b, c) * (n - 1).
struct NodeGrid {
  int nodesX = 0, nodesY = 0, nodesZ = 0;
  int nodeCells = 0;
  static NodeGrid of(const QuantisedStacks& stacks, const QuadParams& params);
  std::array<int, 3> origin(NodeKey key) const;
  std::size_t count() const { return std::size_t(nodesX) * std::size_t(nodesY) * std::size_t(nodesZ); }
};

// False when the node's raw density is uniform (every column it reads all air or all solid over
// its height range): such a node has no cell with a vertex and the pipeline can skip it.
bool nodeMayHaveSurface(const QuantisedStacks& stacks, const QuadParams& params, NodeKey key,
                        const NodeGrid& grid);
// Every node of the grid that may have a surface, x fastest then y then z.
std::vector<NodeKey> nodesWithSurface(const QuantisedStacks& stacks, const QuadParams& params);

// One density sample: the coverage per material channel.
using DensitySample = std::array<std::uint32_t, kMaterialChannels>;

// A box of samples, x fastest: the raw density (rawSide^3), the passes' intermediates and the
// smoothed density (smoothSide^3).
struct DensityVolume {
  int sizeX = 0, sizeY = 0, sizeZ = 0;
  std::vector<DensitySample> samples;
  std::size_t index(int x, int y, int z) const {
    return std::size_t(x) + std::size_t(sizeX) * (std::size_t(y) + std::size_t(sizeY) * std::size_t(z));
  }
};

// The seed's per-cell lookup table.
struct CellEntry {
  std::uint32_t code = 0;         // dc::cellCode: classification, owned quads, vertex bit
  std::uint32_t vertexIndex = 0;  // when the cell has a vertex
  std::uint32_t indexOffset = 0;  // first of its 6 indices per owned quad
  std::uint32_t padding = 0;
  bool operator==(const CellEntry&) const = default;
};

// A mesh vertex as the GPU stores it (std430, 48 bytes).
struct StackVertex {
  std::array<float, 4> position{};   // world metres (x east, y north, z up), w = level
  std::array<float, 4> normal{};     // unit, outward, w = 0
  std::array<float, 4> materials{};  // weights of the material channels, summing to 1
};

// The global counters the allocation adds to; its first five words are a
// DrawElementsIndirectCommand, so the GPU mesh is drawn without reading the counts back.
struct QuadCounters {
  std::uint32_t indexCount = 0;  // 6 per quad
  std::uint32_t instanceCount = 1;
  std::uint32_t firstIndex = 0;
  std::uint32_t baseVertex = 0;
  std::uint32_t baseInstance = 0;
  std::uint32_t vertexCount = 0;
  std::uint32_t padding[2] = {0, 0};
};

struct StackMesh {
  std::vector<StackVertex> vertices;
  std::vector<std::uint32_t> indices;  // triangles, two per quad
  std::size_t quadCount() const { return indices.size() / 6; }
};

// Milliseconds spent in each stage (summed over the nodes run).
struct QuadStageTimes {
  double density = 0, smooth = 0, classify = 0, allocate = 0, attributes = 0, faces = 0;
  double total() const { return density + smooth + classify + allocate + attributes + faces; }
  QuadStageTimes& operator+=(const QuadStageTimes& other);
};

// The stages, as the compute shaders run them (see above).
DensityVolume densityStage(const QuantisedStacks& stacks, const QuadParams& params,
                           std::array<int, 3> origin);
DensityVolume smoothStage(const DensityVolume& raw, const QuadParams& params);
std::vector<CellEntry> classifyStage(const DensityVolume& smoothed, const QuadParams& params);
// Rows (j, k) in order j + n * k, each taking its first vertex and index from `counters`.
void allocateStage(std::vector<CellEntry>& cells, const QuadParams& params, QuadCounters& counters);
void attributesStage(const DensityVolume& smoothed, const std::vector<CellEntry>& cells,
                     const QuantisedStacks& stacks, const QuadParams& params,
                     std::array<int, 3> origin, std::vector<StackVertex>& vertices);
void facesStage(const std::vector<CellEntry>& cells, const QuadParams& params,
                std::vector<std::uint32_t>& indices);

// Per-cell pieces of the stages, shared with the stitched pipeline (lod/stacks): the
// classification of cell (i, j, k) of a smoothed volume whose sample 0 is node-local -1, and
// its vertex (a cell with a vertex), placed in the world with the geometry of `stacks`
// (spacingM, cellM, baseM) for a volume whose cell (0, 0, 0) is sample `origin`.
unsigned cellClassification(const DensityVolume& smoothed, int i, int j, int k,
                            std::uint32_t isoTwice);
StackVertex cellVertex(const DensityVolume& smoothed, int i, int j, int k,
                       const QuantisedStacks& stacks, std::uint32_t isoTwice,
                       std::array<int, 3> origin);
// Only the vertex's position (world metres); reads no sample beyond the cell's corners.
std::array<float, 3> cellVertexPosition(const DensityVolume& smoothed, int i, int j, int k,
                                        const QuantisedStacks& stacks, std::uint32_t isoTwice,
                                        std::array<int, 3> origin);

// The whole pipeline for one node, appended to `mesh` (its sizes are the counters' start).
// `cells` receives the node's lookup table and `times` the stage times when not null.
void quadrangulateNode(const QuantisedStacks& stacks, const QuadParams& params,
                       std::array<int, 3> origin, StackMesh& mesh,
                       std::vector<CellEntry>* cells = nullptr, QuadStageTimes* times = nullptr);

// Every node of `nodes` on all cores (oneTBB), the node meshes concatenated in `nodes`' order
// (deterministic). Vertices of cells shared by neighbouring nodes appear once per node.
StackMesh quadrangulateNodes(const QuantisedStacks& stacks, const QuadParams& params,
                             const std::vector<NodeKey>& nodes, QuadStageTimes* times = nullptr);

}  // namespace tellus
