#pragma once
// Seam blending (beyond the seed): where a node meets a coarser one, stitching gives the finer
// node's border cells the coarser surface, so the surface steps by up to a coarser cell at the
// border (thin walls that shade as dark or light lines). The finer node therefore takes the
// coarser surface over a band of cells next to it: a vertex moves towards its morph target
// (MorphTarget, the coarser level's vertex of the coarse cell that holds it) by a weight that is
// 1 one cell from the coarser node and falls linearly to 0 over `bandCells` cells. The blend is
// baked into the node's mesh when it is made (quadrangulateStitchedNode's seamBandCells,
// shaders/stacks/attributes.comp): the weight depends only on the node's stitch mask, which is
// part of its mesh's cache key, so drawing costs nothing more.
//
// The weight depends only on the vertex's cell and on which coarser nodes lie near it, which
// every node sharing the vertex sees alike:
//   - a coarser leaf within bandCells + 1 < n - 1 cells of a vertex of node F touches F's
//     26-neighbourhood, so it is one of F's parent's neighbours: F's stitch mask names it
//     (SelectedNode::stitchMask). A same-level neighbour E that shares the vertex has it in its
//     own mask for the same reason, and both measure from the same global cell: same weight;
//   - a vertex F shares with a finer neighbour G (G's stitched cells copy F's vertex unmoved)
//     lies at least (n - 1) / 2 cells from any coarser leaf (the selection is balanced: G and
//     that leaf are two levels apart, so not neighbours), so its weight is 0 when
//     bandCells <= (n - 1) / 2 - 1, which seamBandLimit() gives.
// The attributes pass (shaders/stacks/seam_weight.glsl) computes the same in integers.
#include <array>
#include <cstdint>

#include "tellus/lod/stacks/stitched_quadrangulation.hpp"

namespace tellus {

// The largest band that keeps vertices shared with finer neighbours in place (see above).
constexpr int seamBandLimit(int nodeCells) { return (nodeCells - 1) / 2 - 1; }

// A node's seam bits: its stitch mask (bits 0..26, neighbourBit()) and which child of its parent
// it is (bits 27..29: x, y, z halves).
std::uint32_t seamBits(std::uint32_t stitchMask, int keyX, int keyY, int keyZ);

// The blend weight of a vertex in node-local cell `cell` (0..n-1 on each axis) of a node with
// `seam` bits: 1 within one cell of a coarser neighbour, falling linearly to 0 at bandCells + 1
// cells; 0 everywhere when bandCells is 0.
float seamBlendWeight(std::array<int, 3> cell, std::uint32_t seam, int nodeCells, int bandCells);

// MorphTarget's w: the vertex's border bits (bits 0..5, as before) and its node-local cell
// (6 bits an axis from bit 6: x, y, z); at most 2^24, exact in a float.
float packMorphTargetCell(std::array<int, 3> cell, int nodeCells);
std::array<int, 3> morphTargetCell(const MorphTarget& target);
unsigned morphTargetBorderBits(const MorphTarget& target);

// MorphTarget's material weights: four unorm8 (GLSL's packUnorm4x8: round(clamp(w, 0, 1) 255),
// channel 0 in the low byte), the uint's bits in a float.
float packMaterials(const std::array<float, 4>& weights);
std::array<float, 4> unpackMaterials(float packed);

// The seam blend of a vertex: `weight` of the way from `own` to `target` (the coarse vertex):
// position and material weights target w + own (1 - w), the normal the same, renormalised
// (the CPU reference of attributes.comp's blend).
StackVertex seamBlendedVertex(const StackVertex& own, const StackVertex& target, float weight);

// How much of its own shape a stacks vertex keeps where it is drawn (the CPU reference of
// shaders/stacks/vertex_morph.glsl): the node's geomorph factor (0: at the targets, 1: its own
// shape), or 1 when a node sharing the vertex is among `unlikeNeighbours` (neighbourBit()s of
// the same-level neighbours that do not slide as this node does).
float morphKeep(const MorphTarget& target, float morphFactor, std::uint32_t unlikeNeighbours);

// The vertex as drawn: position target + (own - target) keep; normal the same blend,
// renormalised; material weights the same blend of the target's (unpacked) and its own.
StackVertex drawnStackVertex(const StackVertex& own, const MorphTarget& target, float morphFactor,
                             std::uint32_t unlikeNeighbours);
// Its position only.
std::array<float, 3> drawnStackVertexPosition(const std::array<float, 3>& own,
                                              const MorphTarget& target, float morphFactor,
                                              std::uint32_t unlikeNeighbours);

}  // namespace tellus
