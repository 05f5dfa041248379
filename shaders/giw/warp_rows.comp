#version 450
// GIW pass 1 of 2, a work group a sketch row: the row's importance (importance.glsl), then its
// samples moved to equal shares of it and its total importance (warpRowsThenColumns, rows). The
// last group to finish then makes the one distribution of all columns from every row's total
// (warpRowsThenColumns, columns): every output row's sketch row coordinate.
layout(local_size_x = 64) in;
#include "giw/giw_warp_common.glsl"
#include "giw/importance.glsl"
#include "giw/equal_shares.glsl"

// Rows finished this pass; the last row's group sets it back to 0 for the next.
layout(std430, binding = 6) coherent buffer RowsDone { uint rowsDone; };

shared bool lastRow;

void main() {
  int j = int(gl_WorkGroupID.x);
  int first = j * uSize;
  for (int i = int(gl_LocalInvocationID.x); i < uSize; i += int(gl_WorkGroupSize.x)) {
    importance[first + i] = importanceAt(ivec2(i, j));
  }
  memoryBarrierBuffer();
  barrier();
  if (gl_LocalInvocationIndex == 0u) {
    float total = 0.0;
    for (int i = 0; i < uSize; ++i) total += importance[first + i];
    rowTotals[j] = total;
    equalShares(kRowOfImportance, first, uSize, first);
    memoryBarrierBuffer();  // the total reaches memory before the row counts as done
    lastRow = atomicAdd(rowsDone, 1u) == uint(uSize - 1);
  }
  barrier();
  if (lastRow && gl_LocalInvocationIndex == 0u) {
    memoryBarrierBuffer();
    equalShares(kRowTotals, 0, uSize, uSize * uSize);
    rowsDone = 0u;
  }
}
