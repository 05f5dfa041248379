#version 450
// Fractal decoding, pass 2 of 2 per iteration: every working value from its range's parameters,
// value = mean + round(s * (shrunk domain - domain mean)), clamped to the working range; one
// workgroup layer per decoder slot.
layout(local_size_x = 8, local_size_y = 8) in;

layout(binding = 0, rgba32ui) readonly uniform uimage2DArray uParams;
layout(binding = 1, r32ui) readonly uniform uimage2DArray uWorking;
layout(binding = 2, r32ui) readonly uniform uimage2DArray uDomainMeans;
layout(binding = 3, r32ui) writeonly uniform uimage2DArray uNext;
#include "fractal/fractal_code.glsl"
uniform int uSide;     // padded side, samples
uniform int uMinLog2;  // smallest range size, log2

void main() {
  ivec2 p = ivec2(gl_GlobalInvocationID.xy);
  if (p.x >= uSide || p.y >= uSide) return;
  ivec2 cell = p >> uMinLog2;
  int layer = slotLayer();
  RangeParams range = unpackRange(imageLoad(uParams, ivec3(cell, layer)));
  uint value = range.mean;
  if (range.scale != 0) {
    int r = 1 << range.sizeLog2;
    ivec2 uv = isometryPosition(range.isometry, p - range.origin, r);
    int deviation = int(shrunkSample(range.domain, uv, layer)) -
                    int(imageLoad(uDomainMeans, ivec3(cell, layer)).x);
    int v = int(range.mean) + ((range.scale * deviation + (1 << (kScaleBits - 1))) >> kScaleBits);
    value = uint(clamp(v, 0, int(kMaxWorking)));
  }
  imageStore(uNext, ivec3(p, layer), uvec4(value));
}
