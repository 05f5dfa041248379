// Where and how a stacks vertex is drawn (`stacks` only; the CPU reference is drawnStackVertex in
// lod/stacks/seam_blend.hpp): its own position, normal and material weights moved towards its
// morph target's (the next coarser level's surface) by
//   - the seam blend: a weight 1 one cell from a coarser neighbour node, falling linearly to 0
//     over uSeamBandCells cells, from the node's seam bits (its stitch mask, bits 0..26, and
//     which child of its parent it is, bits 27..29) and the vertex's cell (the target's w);
//   - the geomorph: the node's factor (0: at the targets, 1: its own shape), unless a node that
//     shares the vertex is among the unlike neighbours (bit (dx + 1) + 3 (dy + 1) + 9 (dz + 1):
//     another timing, or none there): then every node holding it keeps it in one place.
// keep = factor (1 - weight); every node sharing a vertex computes the same numbers.
uniform int uNodeCells;      // n: cells a node spans on each axis, its overlap included
uniform int uSeamBandCells;  // 0: no seam blend (already limited to (n - 1) / 2 - 1)

float seamBlendWeight(ivec3 cell, uint seam) {
  uint mask = seam & ((1u << 27) - 1u);
  if (uSeamBandCells <= 0 || mask == 0u) return 0.0;
  int span = uNodeCells - 1;
  ivec3 parentLow = -ivec3(int((seam >> 27) & 1u), int((seam >> 28) & 1u), int((seam >> 29) & 1u)) * span;
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
  int steps = clamp(uSeamBandCells + 1 - nearest, 0, uSeamBandCells);
  return float(steps) / float(uSeamBandCells);
}

// How much of its own shape the vertex keeps (the CPU reference's morphKeep). `target`: the
// MorphTarget's first vec4 (position, cell bits).
float morphKeep(vec4 target, float morphFactor, uint unlikeNeighbours, uint seam) {
  uint cellBits = uint(target.w + 0.5);
  ivec3 low = ivec3(0), high = ivec3(0);  // offsets of the nodes sharing the vertex
  for (int a = 0; a < 3; ++a) {
    if ((cellBits & (1u << (2 * a))) != 0u) low[a] = -1;
    if ((cellBits & (1u << (2 * a + 1))) != 0u) high[a] = 1;
  }
  bool pinned = false;
  for (int dz = low.z; dz <= high.z; ++dz)
    for (int dy = low.y; dy <= high.y; ++dy)
      for (int dx = low.x; dx <= high.x; ++dx)
        pinned = pinned || (unlikeNeighbours & (1u << uint((dx + 1) + 3 * (dy + 1) + 9 * (dz + 1)))) != 0u;
  ivec3 cell = ivec3((cellBits >> 6) & 63u, (cellBits >> 12) & 63u, (cellBits >> 18) & 63u);
  float slide = pinned ? 1.0 : morphFactor;
  return slide * (1.0 - seamBlendWeight(cell, seam));
}

// The vertex as drawn (the CPU reference's drawnStackVertex): position, normal (renormalised)
// and material weights blended between the target's (two vec4: position and cell bits, normal
// and packed weights) and its own by `keep`.
void morphStackVertex(inout vec4 position, inout vec4 normal, inout vec4 materials, vec4 target,
                      vec4 targetShading, float keep) {
  if (!(keep < 1.0)) return;
  position.xyz = target.xyz * (1.0 - keep) + position.xyz * keep;
  vec3 n = targetShading.xyz * (1.0 - keep) + normal.xyz * keep;
  float len = length(n);
  if (len > 0.0) normal.xyz = n / len;
  vec4 targetMaterials = unpackUnorm4x8(floatBitsToUint(targetShading.w));
  materials = targetMaterials * (1.0 - keep) + materials * keep;
}
