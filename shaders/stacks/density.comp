#version 450
// Stage 1, stacks to density: one invocation per stack (column u, v of a node's raw volume),
// rasterising its layers into the column's cells like a line; coverage per material channel in
// 1/kSubCell of a cell, layers sharing a cell add up. z of the invocation: the batch node.
layout(local_size_x = 8, local_size_y = 8) in;
#include "stacks/quad_common.glsl"
layout(std430, binding = 3) buffer RawDensity { uvec4 raw[]; };
uniform ivec2 uStackSize;  // stacks (width, height)

int cellOf(int units) {  // floor division by kSubCell
  return units >= 0 ? units / kSubCell : -((-units + kSubCell - 1) / kSubCell);
}

void main() {
  ivec3 id = ivec3(gl_GlobalInvocationID);
  if (id.x >= uRawSide || id.y >= uRawSide || id.z >= uBatchCount) return;
  int shift = 1 + uFilterRadius;
  ivec3 origin = nodeOrigins[id.z].xyz - ivec3(shift);
  int base = id.z * rawBlock() + id.x + uRawSide * id.y;
  int stride = uRawSide * uRawSide;
  for (int w = 0; w < uRawSide; ++w) raw[base + stride * w] = uvec4(0u);
  ivec2 stack = origin.xy + id.xy;
  if (any(lessThan(stack, ivec2(0))) || any(greaterThanEqual(stack, uStackSize))) return;
  // Sample y runs north: row height - 1 - y; the offsets are stored by sample (x + width * y).
  uint column = uint(stack.x + uStackSize.x * stack.y);
  for (uint l = stackOffsets[column]; l < stackOffsets[column + 1u]; ++l) {
    QuantisedLayer layer = stackLayers[l];
    int first = max(cellOf(layer.bottom), origin.z);
    int last = min(cellOf(layer.top - 1), origin.z + uRawSide - 1);
    for (int cell = first; cell <= last; ++cell) {
      int low = max(layer.bottom, cell * kSubCell);
      int high = min(layer.top, (cell + 1) * kSubCell);
      uint cover = high > low ? uint(high - low) : 0u;
      int at = base + stride * (cell - origin.z);
      uvec4 value = raw[at];
      value[layer.channel] += cover;
      raw[at] = value;
    }
  }
}
