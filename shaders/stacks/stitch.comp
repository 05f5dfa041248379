#version 450
// Stitching, topology fitting (seed 003, section 3.4.2): every smoothed sample of a stitched
// node at a corner of a coarse cell takes the coarser level's sample at half its index,
// rounded down (point sampling); invocation x: a smoothed sample, y: the batch node.
layout(local_size_x = 64) in;
#include "stacks/quad_common.glsl"
layout(std430, binding = 4) buffer Smoothed { uvec4 smoothed[]; };
layout(std430, binding = 9) readonly buffer CoarseSmoothed { uvec4 coarseSmoothed[]; };

void main() {
  int node = int(gl_GlobalInvocationID.y);
  int linear = int(gl_GlobalInvocationID.x);
  int side = uSmoothSide;
  if (node >= uBatchCount || linear >= side * side * side) return;
  if (nodes[node].stitch.w == 0) return;
  ivec3 s = ivec3(linear % side, (linear / side) % side, linear / (side * side)) - 1;
  if (!coarseSample(node, s)) return;
  ivec3 q = halfDown(s) + 1;
  int cs = uCoarseSmoothSide;
  smoothed[node * rawBlock() + linear] =
      coarseSmoothed[node * coarseBlock() + q.x + cs * (q.y + cs * q.z)];
}
