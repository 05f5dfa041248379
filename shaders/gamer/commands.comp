#version 450
// GAMeR pass 3, one invocation: each pattern's run of instances (a prefix sum of the counts, in
// pattern order like the CPU's) and its indirect draw command; the frame's totals.
layout(local_size_x = 1) in;
#include "gamer/gamer_select_common.glsl"

void main() {
  uint next = 0u, triangles = 0u, used = 0u;
  for (int p = 0; p < uPatternCount; ++p) {
    uint count = counts[p];
    uvec2 pattern = patterns[p];
    commands[p] = DrawCommand(pattern.x, count, pattern.y, 0u, next);
    next += count;
    triangles += count * (pattern.x / 3u);
    used += count > 0u ? 1u : 0u;
  }
  stats = uvec4(next, triangles, used, 0u);
}
