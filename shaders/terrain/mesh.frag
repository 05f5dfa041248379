#version 450 core
// Shading for explicit meshes: the same model as the reference renderer, with the normal of
// each triangle (from screen-space derivatives) since a mesh carries no height texture.
#include "common/shading.glsl"

in float vHeight;
in vec3 vRelativePosition;
out vec4 fragColour;

void main() {
  vec3 normal = normalize(cross(dFdx(vRelativePosition), dFdy(vRelativePosition)));
  if (normal.z < 0.0) normal = -normal;
  fragColour = vec4(shadeTerrain(vHeight, normal, vRelativePosition), 1.0);
}
