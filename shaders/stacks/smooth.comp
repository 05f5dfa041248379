#version 450
// Stage 2, separable smoothing: one pass per axis (uAxis 0, 1, 2), each shrinking its axis by
// 2r; invocation x: an output sample of the node, y: the batch node. Volumes of uVolumeSide^3
// samples a node (the node's, or the coarser level's of a stitched node).
layout(local_size_x = 64) in;
#include "stacks/quad_common.glsl"
layout(std430, binding = 3) readonly buffer Input { uvec4 inVolume[]; };
layout(std430, binding = 4) writeonly buffer Output { uvec4 outVolume[]; };
uniform int uAxis;
uniform ivec3 uInSize;
uniform int uTaps[9];  // 2r + 1 integer weights
uniform int uVolumeSide;

void main() {
  int node = int(gl_GlobalInvocationID.y);
  ivec3 outSize = uInSize - 2 * uFilterRadius * ivec3(uAxis == 0, uAxis == 1, uAxis == 2);
  int linear = int(gl_GlobalInvocationID.x);
  if (node >= uBatchCount || linear >= outSize.x * outSize.y * outSize.z) return;
  ivec3 p = ivec3(linear % outSize.x, (linear / outSize.x) % outSize.y, linear / (outSize.x * outSize.y));
  ivec3 step = ivec3(uAxis == 0, uAxis == 1, uAxis == 2);
  int block = node * uVolumeSide * uVolumeSide * uVolumeSide;
  uvec4 sum = uvec4(0u);
  for (int t = 0; t <= 2 * uFilterRadius; ++t) {
    ivec3 q = p + t * step;
    sum += uint(uTaps[t]) * inVolume[block + q.x + uInSize.x * (q.y + uInSize.y * q.z)];
  }
  outVolume[block + linear] = sum;
}
