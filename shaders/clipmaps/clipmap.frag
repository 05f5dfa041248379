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
layout(binding = 0) uniform sampler2DArray uHeights;
// The screen-space error shading: the geometric error (metres) of every store tile, a layer a
// clipmap level, row 0 north; this level's and the coarser one's layers, tile counts (x, y:
// this level's and the coarser one's) and the full-resolution samples a tile spans.
layout(binding = 2) uniform sampler2DArray uTileErrorM;
uniform ivec2 uErrorLayers;
uniform ivec2 uErrorTiles, uCoarserErrorTiles;
uniform vec2 uErrorSpanSamples;

in vec3 vRelativePosition;
in float vHeight;
in vec3 vFineUV;
in vec3 vCoarseUV;
in vec2 vSample;
in float vBlend;
flat in int vLevel;
out vec4 fragColour;

// The geometric error of the store tile under full-resolution sample `at` in `layer`.
float tileErrorM(vec2 at, int layer, ivec2 tiles, float span) {
  ivec2 tile = clamp(ivec2(floor(at / span)), ivec2(0), tiles - 1);
  return texelFetch(uTileErrorM, ivec3(tile, layer), 0).r;
}

void main() {
  if (any(lessThan(vSample, vec2(0.0))) || any(greaterThan(vSample, uGridMax))) discard;
  vec2 texel = 1.0 / vec2(textureSize(uHeights, 0).xy);
  vec3 fine = heightfieldNormalArray(uHeights, vFineUV, texel, uSpacing * uScale, uExaggeration);
  vec3 coarse = heightfieldNormalArray(uHeights, vCoarseUV, texel, uSpacing * uScale * 2.0, uExaggeration);
  vec3 normal = normalize(mix(fine, coarse, vBlend));
  vec3 lit = shadeTerrain(vHeight, normal, vRelativePosition);
  float errorM = mix(tileErrorM(vSample, uErrorLayers.x, uErrorTiles, uErrorSpanSamples.x),
                     tileErrorM(vSample, uErrorLayers.y, uCoarserErrorTiles, uErrorSpanSamples.y), vBlend) *
                 uExaggeration;
  fragColour = vec4(applyShadingMode(lit, vLevel, errorM, vRelativePosition), 1.0);
}
