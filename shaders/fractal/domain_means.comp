#version 450
// Fractal decoding, pass 1 of 2 per iteration: the mean (floor) of each range's shrunk domain
// in the current working image, one invocation per smallest-range cell, one workgroup layer per
// decoder slot.
layout(local_size_x = 8, local_size_y = 8) in;

layout(binding = 0, rgba32ui) readonly uniform uimage2DArray uParams;
layout(binding = 1, r32ui) readonly uniform uimage2DArray uWorking;
layout(binding = 2, r32ui) writeonly uniform uimage2DArray uDomainMeans;
#include "fractal/fractal_code.glsl"
uniform int uCells;  // cells per side

void main() {
  ivec2 cell = ivec2(gl_GlobalInvocationID.xy);
  if (cell.x >= uCells || cell.y >= uCells) return;
  int layer = slotLayer();
  RangeParams range = unpackRange(imageLoad(uParams, ivec3(cell, layer)));
  uint sum = 0u;
  if (range.scale != 0) {
    int r = 1 << range.sizeLog2;
    for (int v = 0; v < r; ++v) {
      for (int u = 0; u < r; ++u) sum += shrunkSample(range.domain, ivec2(u, v), layer);
    }
  }
  imageStore(uDomainMeans, ivec3(cell, layer), uvec4(sum >> (2 * range.sizeLog2)));
}
