#version 450
// Stage 3, classification: each cell's 8 corners against the iso-value and the quads it owns
// (code = classification | owned quads << 8); x: the cell, y: the batch node.
layout(local_size_x = 64) in;
#include "stacks/quad_common.glsl"
layout(std430, binding = 4) readonly buffer Smoothed { uvec4 smoothed[]; };
layout(std430, binding = 5) buffer Cells { uvec4 cells[]; };  // code, vertex, offset, -
uniform int uIsoTwice;  // twice the iso-value in smoothed units

void main() {
  int node = int(gl_GlobalInvocationID.y);
  int linear = int(gl_GlobalInvocationID.x);
  int n = uNodeCells;
  if (node >= uBatchCount || linear >= cellBlock()) return;
  ivec3 c = ivec3(linear % n, (linear / n) % n, linear / (n * n));
  int block = node * rawBlock();
  uint classification = 0u;
  for (int k = 0; k < 8; ++k) {
    ivec3 s = c + 1 + cornerOffset(k);  // smoothed sample 0 is node-local -1
    uvec4 d = smoothed[block + s.x + uSmoothSide * (s.y + uSmoothSide * s.z)];
    if (2u * (d.x + d.y + d.z + d.w) > uint(uIsoTwice)) classification |= 1u << k;
  }
  cells[node * cellBlock() + linear] = uvec4(classification | (ownedQuads(classification, c, n) << 8), 0u, 0u, 0u);
}
