// The seam blend's weight (lod/stacks/seam_blend.hpp, seamBlendWeight, in the same integers): for
// a vertex in node-local cell `cell` of a node whose parent's first cell is `parentLow` (node-local)
// and whose parent's selected coarser neighbours are `mask` (neighbourBit()s), 1 within one cell
// of a coarser neighbour, falling linearly to 0 at band + 1 cells (the Chebyshev distance in
// cells); 0 when band is 0. `span` is n - 1, the cells from a node's first sample to the next's.
float seamBlendWeight(ivec3 cell, uint mask, ivec3 parentLow, int span, int band) {
  mask &= (1u << 27) - 1u;
  if (band <= 0 || mask == 0u) return 0.0;
  int nearest = 1 << 30;
  while (mask != 0u) {  // the coarser neighbours only (a few bits of 26)
    int bit = findLSB(mask);
    mask &= mask - 1u;
    ivec3 d = ivec3(bit % 3, (bit / 3) % 3, bit / 9) - 1;
    ivec3 low = parentLow + d * 2 * span;
    ivec3 high = low + 2 * span;
    ivec3 outside = max(ivec3(0), max(low - cell, cell - high));
    nearest = min(nearest, max(outside.x, max(outside.y, outside.z)));
  }
  int steps = clamp(band + 1 - nearest, 0, band);
  return float(steps) / float(band);
}
