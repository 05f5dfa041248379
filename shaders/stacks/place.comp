#version 450
// Placement (octree mode), between allocation and attributes: one invocation places the batch's
// nodes one after another in the staging buffers from the cursor that earlier batches left, so
// that nothing is read back before the meshes are written (StackMeshStaging). Each node gets its
// first vertex and first index (NodeInfo.dest.xy) and a placement record the CPU reads a frame
// or more later; a node that does not fit gets the capacities as its firsts (the kernels write
// nothing of it) and is marked not placed. The cursor also sums what every node wanted, placed
// or not, so that the CPU can size the buffers for the next time.
layout(local_size_x = 1) in;

struct NodeInfo {
  ivec4 origin;
  ivec4 stitch;
  uvec4 dest;  // x: first vertex, y: first index, z: its counters
};
struct QuadCounters {
  uint indexCount;
  uint instanceCount;
  uint firstIndex;
  uint baseVertex;
  uint baseInstance;
  uint vertexCount;
  uint padding0, padding1;
};
layout(std430, binding = 2) buffer Nodes { NodeInfo nodes[]; };
layout(std430, binding = 6) readonly buffer Counters { QuadCounters counters[]; };
// [0]: the cursor (vertices, indices placed so far; vertices, indices wanted so far); then one
// placement per node of the staging (first vertex or 0xffffffff: not placed, vertices, first
// index, indices).
layout(std430, binding = 11) buffer Placements { uvec4 placements[]; };

uniform int uBatchCount;
uniform int uFirstPlacement;  // the batch's first node among the staging's nodes
uniform int uStagingVertices, uStagingIndices;  // the staging buffers' capacities

void main() {
  uint vertexCapacity = uint(uStagingVertices), indexCapacity = uint(uStagingIndices);
  uvec4 cursor = placements[0];
  for (int i = 0; i < uBatchCount; ++i) {
    QuadCounters c = counters[nodes[i].dest.z];
    uint vertices = c.vertexCount, indices = c.indexCount;
    cursor.zw += uvec2(vertices, indices);
    bool fits = cursor.x + vertices <= vertexCapacity && cursor.y + indices <= indexCapacity;
    uvec2 first = fits ? cursor.xy : uvec2(vertexCapacity, indexCapacity);
    nodes[i].dest.xy = first;
    placements[1u + uint(uFirstPlacement) + uint(i)] =
        uvec4(fits ? first.x : 0xffffffffu, vertices, first.y, indices);
    if (fits) cursor.xy += uvec2(vertices, indices);
  }
  placements[0] = cursor;
}
