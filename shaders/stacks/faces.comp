#version 450
// Stage 6, faces: each cell writes its owned quads, two triangles each (v0 v1 v2, v0 v2 v3),
// from the vertex indices of the four cells around each crossing edge, counter-clockwise seen
// from outside, at its index-buffer offset. A stitched node's coarse cells look their vertex up
// at their even cell (T-junction removal).
layout(local_size_x = 64) in;
#include "stacks/quad_common.glsl"
layout(std430, binding = 5) readonly buffer Cells { uvec4 cells[]; };
layout(std430, binding = 8) writeonly buffer Indices { uint indices[]; };
uniform int uIndexCapacity;

const ivec3 kQuadCells[12] = ivec3[12](
    ivec3(0, -1, -1), ivec3(0, 0, -1), ivec3(0, 0, 0), ivec3(0, -1, 0),   // x
    ivec3(-1, 0, -1), ivec3(-1, 0, 0), ivec3(0, 0, 0), ivec3(0, 0, -1),   // y
    ivec3(-1, -1, 0), ivec3(0, -1, 0), ivec3(0, 0, 0), ivec3(-1, 0, 0));  // z

void main() {
  int node = int(gl_GlobalInvocationID.y);
  int linear = int(gl_GlobalInvocationID.x);
  int n = uNodeCells;
  if (node >= uBatchCount || linear >= cellBlock()) return;
  int block = node * cellBlock();
  uvec4 cell = cells[block + linear];
  uint quads = codeQuads(cell.x);
  if (quads == 0u) return;
  ivec3 c = ivec3(linear % n, (linear / n) % n, linear / (n * n));
  bool stitched = nodes[node].stitch.w != 0;
  uint offset = nodes[node].dest.y + cell.z;
  for (int axis = 0; axis < 3; ++axis) {
    if (((quads >> axis) & 1u) == 0u) continue;
    uint v[4];
    for (int q = 0; q < 4; ++q) {
      ivec3 p = c + kQuadCells[axis * 4 + q];
      if (stitched && coarseCell(node, p)) p &= ~1;
      v[q] = cells[block + p.x + n * (p.y + n * p.z)].y;
    }
    if (!cornerInside(cell.x, 0)) {
      uint swap = v[1];
      v[1] = v[3];
      v[3] = swap;
    }
    if (offset + 6u <= uint(uIndexCapacity)) {
      indices[offset] = v[0];
      indices[offset + 1u] = v[1];
      indices[offset + 2u] = v[2];
      indices[offset + 3u] = v[0];
      indices[offset + 4u] = v[2];
      indices[offset + 5u] = v[3];
    }
    offset += 6u;
  }
}
