// Where and how a stacks vertex is drawn (`stacks` only; the CPU reference is drawnStackVertex in
// lod/stacks/seam_blend.hpp): its own position, normal and material weights (the seam blend
// already baked in: attributes.comp) moved towards its morph target's (the next coarser level's
// surface) by the node's geomorph factor (0: at the targets, 1: its own shape), unless a node
// that shares the vertex is among the unlike neighbours (bit (dx + 1) + 3 (dy + 1) + 9 (dz + 1):
// another timing, or none there): then every node holding it keeps it in one place. Every node
// sharing a vertex computes the same numbers.

// How much of its own shape the vertex keeps (the CPU reference's morphKeep). `target`: the
// MorphTarget's first vec4 (position, cell bits).
float morphKeep(vec4 target, float morphFactor, uint unlikeNeighbours) {
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
  return pinned ? 1.0 : morphFactor;
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
