#version 450 core
// Shading of the clipmap levels: normals from the level's heights blended with the coarser
// level's by the geomorph weight (texture blending, so shading has no seam at level borders
// either), tinted by the drawn height; fragments outside the terrain's samples are discarded
// (the coarse levels reach past the data).
#include "common/shading.glsl"
#include "common/heightfield.glsl"
#include "common/lod_colours.glsl"

uniform vec2 uSpacing;       // metres per full-resolution sample
uniform float uExaggeration;
uniform float uScale;        // 2^level
uniform vec2 uGridMax;       // the last sample (col, row)
uniform vec2 uLevelErrorM;   // geometric error of this level and of the coarser one, metres
layout(binding = 0) uniform sampler2DArray uHeights;

in vec3 vRelativePosition;
in float vHeight;
in vec3 vFineUV;
in vec3 vCoarseUV;
in vec2 vSample;
in float vBlend;
flat in int vLevel;
out vec4 fragColour;

void main() {
  if (any(lessThan(vSample, vec2(0.0))) || any(greaterThan(vSample, uGridMax))) discard;
  vec2 texel = 1.0 / vec2(textureSize(uHeights, 0).xy);
  vec3 fine = heightfieldNormalArray(uHeights, vFineUV, texel, uSpacing * uScale, uExaggeration);
  vec3 coarse = heightfieldNormalArray(uHeights, vCoarseUV, texel, uSpacing * uScale * 2.0, uExaggeration);
  vec3 normal = normalize(mix(fine, coarse, vBlend));
  vec3 lit = shadeTerrain(vHeight, normal, vRelativePosition);
  float errorM = mix(uLevelErrorM.x, uLevelErrorM.y, vBlend) * uExaggeration;
  fragColour = vec4(applyShadingMode(lit, vLevel, errorM, vRelativePosition), 1.0);
}
