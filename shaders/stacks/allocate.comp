#version 450
// Stage 4, allocation: one invocation per row of cells (along x) counts the row's vertices and
// quads, takes its first vertex index and index-buffer offset with one atomic add each on the
// global counters (whose first words are the indirect draw command), then numbers its cells.
layout(local_size_x = 64) in;
#include "stacks/quad_common.glsl"
layout(std430, binding = 5) buffer Cells { uvec4 cells[]; };
layout(std430, binding = 6) buffer Counters {
  uint indexCount;     // DrawElementsIndirectCommand: count
  uint instanceCount;
  uint firstIndex;
  uint baseVertex;
  uint baseInstance;
  uint vertexCount;
  uint padding[2];
};

void main() {
  int node = int(gl_GlobalInvocationID.y);
  int row = int(gl_GlobalInvocationID.x);
  int n = uNodeCells;
  if (node >= uBatchCount || row >= n * n) return;
  int first = node * cellBlock() + row * n;
  uint vertices = 0u, quads = 0u;
  for (int i = 0; i < n; ++i) {
    uint code = cells[first + i].x;
    if (cellHasVertex(code & 255u)) ++vertices;
    quads += uint(bitCount(code >> 8));
  }
  uint vertex = vertices > 0u ? atomicAdd(vertexCount, vertices) : 0u;
  uint offset = quads > 0u ? atomicAdd(indexCount, 6u * quads) : 0u;
  for (int i = 0; i < n; ++i) {
    uvec4 cell = cells[first + i];
    if (cellHasVertex(cell.x & 255u)) cell.y = vertex++;
    cell.z = offset;
    offset += 6u * uint(bitCount(cell.x >> 8));
    cells[first + i] = cell;
  }
}
