#version 450 core
// Stack terrain meshes from the quadrangulation pipeline, drawn by vertex pulling: the index
// buffer's values are gl_VertexID, the vertices (stacks/quad_common.glsl's StackVertex) are
// read from a storage buffer (a multi-draw's base vertex included). position.w is the level of
// the stack MipMap whose cells made the vertex (0 for stacks-full).
struct StackVertex {
  vec4 position;   // world metres
  vec4 normal;
  vec4 materials;  // weights of rock, soil, grass, other
};
layout(std430, binding = 0) readonly buffer Vertices { StackVertex vertices[]; };
// Geomorphing (`stacks` only, uMorph set): each vertex's target on the next coarser level's
// surface (xyz world metres, w: its node-border bits; lod/stacks/stitched_quadrangulation.hpp)
// and, per node (a draw's base instance), its morph factor (0: at the targets, 1: its own
// shape) and the neighbours that do not morph as it does (bit (dx + 1) + 3 (dy + 1) +
// 9 (dz + 1) for the same-level neighbour at offset d: another timing, or none there). A
// vertex in border cells is shared with the neighbours across those borders: it stays put
// when any of them does not morph with it, so every node sharing it keeps it in one place.
layout(std430, binding = 1) readonly buffer MorphTargets { vec4 morphTargets[]; };
layout(location = 0) in float aMorphFactor;
layout(location = 1) in uint aUnlikeNeighbours;
uniform int uMorph;

uniform mat4 uViewProjection;  // camera-relative world -> clip
uniform vec3 uCameraPosition;  // world metres
uniform float uExaggeration;   // vertical scale
uniform float uFinestCellM;    // the finest level's cell size, metres (the error shading)

out vec3 vRelativePosition;
out vec3 vNormal;
out vec4 vMaterials;
flat out int vLevel;
out float vErrorM;

void main() {
  StackVertex v = vertices[gl_VertexID];
  if (uMorph != 0) {
    vec4 target = morphTargets[gl_VertexID];
    uint border = uint(target.w + 0.5);
    ivec3 low = ivec3(0), high = ivec3(0);  // offsets of the nodes sharing the vertex
    for (int a = 0; a < 3; ++a) {
      if ((border & (1u << (2 * a))) != 0u) low[a] = -1;
      if ((border & (1u << (2 * a + 1))) != 0u) high[a] = 1;
    }
    bool pinned = false;
    for (int dz = low.z; dz <= high.z; ++dz)
      for (int dy = low.y; dy <= high.y; ++dy)
        for (int dx = low.x; dx <= high.x; ++dx)
          pinned = pinned || (aUnlikeNeighbours & (1u << ((dx + 1) + 3 * (dy + 1) + 9 * (dz + 1)))) != 0u;
    if (!pinned && aMorphFactor < 1.0) v.position.xyz = mix(target.xyz, v.position.xyz, aMorphFactor);
  }
  vec3 position = vec3(v.position.xy, v.position.z * uExaggeration) - uCameraPosition;
  vRelativePosition = position;
  // Normals of a surface scaled vertically by e: (nx, ny, nz / e), renormalised.
  vNormal = normalize(vec3(v.normal.xy, v.normal.z / max(uExaggeration, 1e-3)));
  vMaterials = v.materials;
  vLevel = int(v.position.w + 0.5);
  // A level-k cell is 2^k finest cells: its surface may be off by about half of the difference.
  vErrorM = 0.5 * (exp2(v.position.w) - 1.0) * uFinestCellM * uExaggeration;
  gl_Position = uViewProjection * vec4(position, 1.0);
}
