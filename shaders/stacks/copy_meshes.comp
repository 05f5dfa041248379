#version 450
// Copies node meshes from a staging into the mesh pool (octree mode, StackMeshCopy): one work
// group per node, its 64 invocations striding over the node's vertex words (a StackVertex is 12
// words), index words and, with geomorph targets, target words (a MorphTarget is 8 words). One
// dispatch for every mesh that came back in a frame, where a copy command per buffer and node
// would cost the driver thousands of calls.
layout(local_size_x = 64) in;

// Element ranges of one node: source firsts in the staging, target firsts in the pool.
struct MeshCopy {
  uint sourceVertex, targetVertex, vertexCount;
  uint sourceIndex, targetIndex, indexCount;
  uint padding0, padding1;
};
layout(std430, binding = 0) readonly buffer Copies { MeshCopy copies[]; };
layout(std430, binding = 1) readonly buffer SourceVertices { uint sourceVertices[]; };
layout(std430, binding = 2) readonly buffer SourceIndices { uint sourceIndices[]; };
layout(std430, binding = 3) readonly buffer SourceTargets { uint sourceTargets[]; };
layout(std430, binding = 4) writeonly buffer PoolVertices { uint poolVertices[]; };
layout(std430, binding = 5) writeonly buffer PoolIndices { uint poolIndices[]; };
layout(std430, binding = 6) writeonly buffer PoolTargets { uint poolTargets[]; };

uniform int uFirstCopy;      // this dispatch's first entry of copies[]
uniform int uMorphTargets;   // 1: copy the geomorph targets too

const uint kVertexWords = 12u, kTargetWords = 8u;

void main() {
  MeshCopy c = copies[uint(uFirstCopy) + gl_WorkGroupID.x];
  uint step = gl_WorkGroupSize.x;
  uint vertexWords = c.vertexCount * kVertexWords;
  for (uint w = gl_LocalInvocationID.x; w < vertexWords; w += step) {
    poolVertices[c.targetVertex * kVertexWords + w] = sourceVertices[c.sourceVertex * kVertexWords + w];
  }
  for (uint w = gl_LocalInvocationID.x; w < c.indexCount; w += step) {
    poolIndices[c.targetIndex + w] = sourceIndices[c.sourceIndex + w];
  }
  if (uMorphTargets == 0) return;
  uint targetWords = c.vertexCount * kTargetWords;
  for (uint w = gl_LocalInvocationID.x; w < targetWords; w += step) {
    poolTargets[c.targetVertex * kTargetWords + w] = sourceTargets[c.sourceVertex * kTargetWords + w];
  }
}
