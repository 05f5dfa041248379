#version 450
// Stage 4, allocation: one invocation per row of cells (along x) counts the row's vertices and
// quads, takes its first vertex index and index-buffer offset with one atomic add each on the
// node's counters (whose first words are an indirect draw command), then numbers its cells.
// Nodes share counters when their meshes append to one buffer (stacks-full), or each has its
// own (the octree: vertex and index numbers count from the node's own first).
layout(local_size_x = 64) in;
#include "stacks/quad_common.glsl"
layout(std430, binding = 5) buffer Cells { uvec4 cells[]; };
struct QuadCounters {
  uint indexCount;  // DrawElementsIndirectCommand: count
  uint instanceCount;
  uint firstIndex;
  uint baseVertex;
  uint baseInstance;
  uint vertexCount;
  uint padding0, padding1;
};
layout(std430, binding = 6) buffer Counters { QuadCounters counters[]; };

void main() {
  int node = int(gl_GlobalInvocationID.y);
  int row = int(gl_GlobalInvocationID.x);
  int n = uNodeCells;
  if (node >= uBatchCount || row >= n * n) return;
  int first = node * cellBlock() + row * n;
  uint vertices = 0u, quads = 0u;
  for (int i = 0; i < n; ++i) {
    uint code = cells[first + i].x;
    if (codeHasVertex(code)) ++vertices;
    quads += uint(bitCount(codeQuads(code)));
  }
  uint slot = nodes[node].dest.z;
  uint vertex = vertices > 0u ? atomicAdd(counters[slot].vertexCount, vertices) : 0u;
  uint offset = quads > 0u ? atomicAdd(counters[slot].indexCount, 6u * quads) : 0u;
  for (int i = 0; i < n; ++i) {
    uvec4 cell = cells[first + i];
    if (codeHasVertex(cell.x)) cell.y = vertex++;
    cell.z = offset;
    offset += 6u * uint(bitCount(codeQuads(cell.x)));
    cells[first + i] = cell;
  }
}
