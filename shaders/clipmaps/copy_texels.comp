#version 450
// Clipmap update, GPU side: stores the texels a worker staged (clipmap_texel_staging.hpp) into the
// height texture array. One invocation a texel; the staged texels are the update's rectangles one
// after another, each row by row, so a texel finds its rectangle by a binary search over their
// first texels.
layout(local_size_x = 64) in;

struct StagedRect {
  ivec4 placement;  // first texel x, y in the layer, the layer (level), the rectangle's width
  uvec4 first;      // x: its first texel in the staged texels
};

layout(std430, binding = 0) readonly buffer Texels { vec2 texels[]; };
layout(std430, binding = 1) readonly buffer Rects { StagedRect rects[]; };
layout(rg32f, binding = 0) writeonly uniform image2DArray uHeights;

uniform int uRectCount;
uniform int uTexelCount;

void main() {
  uint t = gl_GlobalInvocationID.x;
  if (t >= uint(uTexelCount)) return;
  // The last rectangle whose first texel is at or before t.
  int lo = 0, hi = uRectCount - 1;
  while (lo < hi) {
    int mid = (lo + hi + 1) / 2;
    if (rects[mid].first.x <= t) lo = mid; else hi = mid - 1;
  }
  StagedRect rect = rects[lo];
  uint local = t - rect.first.x;
  uint width = uint(rect.placement.w);
  ivec2 texel = rect.placement.xy + ivec2(int(local % width), int(local / width));
  imageStore(uHeights, ivec3(texel, rect.placement.z), vec4(texels[t], 0.0, 0.0));
}
