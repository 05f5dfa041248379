#version 450
// GAMeR pass 2 of 2: every chosen coarse triangle into its pattern's run of instances.
layout(local_size_x = 64) in;
#include "gamer/gamer_select_common.glsl"

void main() {
  uint triangle = gl_GlobalInvocationID.x;
  if (triangle >= uint(2 * uCellsX * uCellsY)) return;
  Chosen c = chosen[triangle];
  if (c.pattern == 0xffffffffu) return;
  instances[commands[c.pattern].baseInstance + c.rank] = c.instance;
}
