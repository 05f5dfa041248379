#version 450 core
// Shading of the globe reference: the hypsometric tint and sun light of the flat renderers, each
// point lit in its own east-north-up frame. The reference draws every sample: its screen-space
// error is 0 (green in the error view).
#include "common/shading.glsl"
#include "common/lod_colours.glsl"

in vec3 vNormal;
in vec3 vSun;
in float vHeight;
in vec3 vRelativePosition;
out vec4 fragColour;

void main() {
  vec3 lit = shadeTerrainWithSun(vHeight, normalize(vNormal), normalize(vSun), vRelativePosition);
  fragColour = vec4(applyShadingMode(lit, 0, 0.0, vRelativePosition), 1.0);
}
