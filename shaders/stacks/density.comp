#version 450
// Stage 1, stacks to density: one invocation per stack (column u, v of a node's raw volume),
// rasterising its layers into the column's cells like a line; coverage per material channel in
// 1/kSubCell of a cell, layers sharing a cell add up. z of the invocation: the batch node.
// The coarse pass (uCoarsePass) fills a node's volume of the next coarser level instead, from
// half its origin (stitched_quadrangulation.hpp): stitching and the geomorph targets read it
// (level + 1 past the last level: an empty layout, so zero density).
layout(local_size_x = 8, local_size_y = 8) in;
#include "stacks/quad_common.glsl"
layout(std430, binding = 3) buffer RawDensity { uvec4 raw[]; };
uniform int uVolumeSide;  // this pass's raw volume side
uniform int uCoarsePass;

int cellOf(int units) {  // floor division by kSubCell
  return units >= 0 ? units / kSubCell : -((-units + kSubCell - 1) / kSubCell);
}

void main() {
  ivec3 id = ivec3(gl_GlobalInvocationID);
  int side = uVolumeSide;
  if (id.x >= side || id.y >= side || id.z >= uBatchCount) return;
  int shift = 1 + uFilterRadius;
  int level = nodes[id.z].origin.w;
  ivec3 origin = nodes[id.z].origin.xyz;
  if (uCoarsePass != 0) {
    origin = origin / 2;  // even origins: exact
    level += 1;
  }
  origin -= ivec3(shift);
  int base = id.z * side * side * side + id.x + side * id.y;
  int stride = side * side;
  for (int w = 0; w < side; ++w) raw[base + stride * w] = uvec4(0u);
  if (level >= 16) return;
  ivec4 layout_ = uLevelLayout[level];
  ivec2 stack = origin.xy + id.xy;
  if (any(lessThan(stack, ivec2(0))) || any(greaterThanEqual(stack, layout_.zw))) return;
  // Sample y runs north: row height - 1 - y; the columns are stored by sample (x + width * y).
  uint column = uint(layout_.x + stack.x + layout_.z * stack.y);
  for (uint l = stackRanges[2u * column]; l < stackRanges[2u * column + 1u]; ++l) {
    QuantisedLayer layer = stackLayers[l];
    int first = max(cellOf(layer.bottom), origin.z);
    int last = min(cellOf(layer.top - 1), origin.z + side - 1);
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
