#version 450 core
// Stack terrain meshes from the quadrangulation pipeline, drawn by vertex pulling: the index
// buffer's values are gl_VertexID, the vertices (stacks/quad_common.glsl's StackVertex) are
// read from a storage buffer.
struct StackVertex {
  vec4 position;   // world metres
  vec4 normal;
  vec4 materials;  // weights of rock, soil, grass, other
};
layout(std430, binding = 0) readonly buffer Vertices { StackVertex vertices[]; };

uniform mat4 uViewProjection;  // camera-relative world -> clip
uniform vec3 uCameraPosition;  // world metres
uniform float uExaggeration;   // vertical scale

out vec3 vRelativePosition;
out vec3 vNormal;
out vec4 vMaterials;

void main() {
  StackVertex v = vertices[gl_VertexID];
  vec3 position = vec3(v.position.xy, v.position.z * uExaggeration) - uCameraPosition;
  vRelativePosition = position;
  // Normals of a surface scaled vertically by e: (nx, ny, nz / e), renormalised.
  vNormal = normalize(vec3(v.normal.xy, v.normal.z / max(uExaggeration, 1e-3)));
  vMaterials = v.materials;
  gl_Position = uViewProjection * vec4(position, 1.0);
}
