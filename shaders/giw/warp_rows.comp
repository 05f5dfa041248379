#version 450
// GIW pass 2: each sketch row's samples moved to equal shares of its importance, and the row's
// total importance (warpRowsThenColumns, rows).
layout(local_size_x = 64) in;
#include "giw/giw_warp_common.glsl"
#include "giw/equal_shares.glsl"

void main() {
  int j = int(gl_GlobalInvocationID.x);
  if (j >= uSize) return;
  int first = j * uSize;
  float total = 0.0;
  for (int i = 0; i < uSize; ++i) total += importance[first + i];
  rowTotals[j] = total;
  equalShares(kRowOfImportance, first, uSize, first);
}
