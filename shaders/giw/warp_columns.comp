#version 450
// GIW pass 3, one invocation: the one distribution of all columns, from each row's total
// importance (warpRowsThenColumns, columns): every output row's sketch row coordinate.
layout(local_size_x = 1) in;
#include "giw/giw_warp_common.glsl"
#include "giw/equal_shares.glsl"

void main() {
  equalShares(kRowTotals, 0, uSize, uSize * uSize);
}
