#version 450 core
#include "common/shading.glsl"
#include "common/heightfield.glsl"
#include "common/lod_colours.glsl"

uniform vec2 uSpacing;
uniform float uExaggeration;
layout(binding = 0) uniform sampler2D uHeights;

in vec2 vTexCoord;
in float vHeight;
in vec3 vRelativePosition;
out vec4 fragColour;

void main() {
  vec2 texel = 1.0 / vec2(textureSize(uHeights, 0));
  vec3 normal = heightfieldNormal(uHeights, vTexCoord, texel, uSpacing, uExaggeration);
  // Every sample is drawn: level of detail 0 and no geometric error everywhere.
  vec3 lit = shadeTerrain(vHeight, normal, vRelativePosition);
  fragColour = vec4(applyShadingMode(lit, 0, 0.0, vRelativePosition), 1.0);
}
