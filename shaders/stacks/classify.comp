#version 450
// Stage 3, classification: each cell's 8 corners against the iso-value, the quads it owns and
// whether it emits a vertex (dc::cellCode); x: the cell, y: the batch node. A stitched node's
// coarse cells emit the vertices of the coarser level's cells, one per coarse cell (its even
// fine cell).
layout(local_size_x = 64) in;
#include "stacks/quad_common.glsl"
layout(std430, binding = 4) readonly buffer Smoothed { uvec4 smoothed[]; };
layout(std430, binding = 5) buffer Cells { uvec4 cells[]; };  // code, vertex, offset, -
layout(std430, binding = 9) readonly buffer CoarseSmoothed { uvec4 coarseSmoothed[]; };
uniform int uIsoTwice;  // twice the iso-value in smoothed units

uint classifyFine(int node, ivec3 c) {
  uint classification = 0u;
  for (int k = 0; k < 8; ++k) {
    ivec3 s = c + 1 + cornerOffset(k);  // smoothed sample 0 is node-local -1
    uvec4 d = smoothed[node * rawBlock() + s.x + uSmoothSide * (s.y + uSmoothSide * s.z)];
    if (2u * (d.x + d.y + d.z + d.w) > uint(uIsoTwice)) classification |= 1u << k;
  }
  return classification;
}

uint classifyCoarse(int node, ivec3 c) {  // coarse-local cell
  uint classification = 0u;
  int cs = uCoarseSmoothSide;
  for (int k = 0; k < 8; ++k) {
    ivec3 s = c + 1 + cornerOffset(k);
    uvec4 d = coarseSmoothed[node * coarseBlock() + s.x + cs * (s.y + cs * s.z)];
    if (2u * (d.x + d.y + d.z + d.w) > uint(uIsoTwice)) classification |= 1u << k;
  }
  return classification;
}

void main() {
  int node = int(gl_GlobalInvocationID.y);
  int linear = int(gl_GlobalInvocationID.x);
  int n = uNodeCells;
  if (node >= uBatchCount || linear >= cellBlock()) return;
  ivec3 c = ivec3(linear % n, (linear / n) % n, linear / (n * n));
  uint classification = classifyFine(node, c);
  bool vertex = cellHasVertex(classification);
  if (nodes[node].stitch.w != 0 && coarseCell(node, c)) {
    vertex = all(equal(c & 1, ivec3(0))) && cellHasVertex(classifyCoarse(node, c / 2));
  }
  uint code = classification | (ownedQuads(classification, c, n) << 8) | (vertex ? kVertexBit : 0u);
  cells[node * cellBlock() + linear] = uvec4(code, 0u, 0u, 0u);
}
