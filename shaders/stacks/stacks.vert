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
// `stacks` only (uMorph set): each vertex's target on the next coarser level's surface (two vec4:
// xyz world metres and w its border bits and cell, then the target's normal and packed material
// weights; lod/stacks/stitched_quadrangulation.hpp's MorphTarget) and, per
// node (a draw's base instance), its geomorph factor and the neighbours that do not slide as it
// does: stacks/vertex_morph.glsl moves the vertex by them.
layout(std430, binding = 1) readonly buffer MorphTargets { vec4 morphTargets[]; };
layout(location = 0) in float aMorphFactor;
layout(location = 1) in uint aUnlikeNeighbours;
uniform int uMorph;
#include "stacks/vertex_morph.glsl"

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
  // Only sliding nodes move their vertices.
  if (uMorph != 0 && aMorphFactor < 1.0) {
    vec4 target = morphTargets[2 * gl_VertexID], targetShading = morphTargets[2 * gl_VertexID + 1];
    float keep = morphKeep(target, aMorphFactor, aUnlikeNeighbours);
    morphStackVertex(v.position, v.normal, v.materials, target, targetShading, keep);
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
