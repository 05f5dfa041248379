#version 450 core
// Shading of the RAG mesh: lit from the height map's normals and tinted by its heights; in the
// screen-space error mode the error is the vertical distance from the drawn surface to the
// reference's triangles (rag::sampleSurface, the harness's truth) under the pixel, plus the
// map's own error when it is a coarser level of the terrain, projected at the pixel's distance
// (the seed's colour-coded error view).
#include "common/shading.glsl"
#include "common/heightfield.glsl"
#include "common/lod_colours.glsl"
#include "rag/rag_common.glsl"

uniform vec2 uSpacing;
uniform float uExaggeration;
uniform float uMapErrorM;  // the height map's own geometric error (a coarser level), metres

in vec2 vTexCoord;
in vec2 vGrid;  // (u, v) of the drawn point, samples
in float vHeight;
in vec3 vRelativePosition;
out vec4 fragColour;

void main() {
  vec2 texel = 1.0 / vec2(textureSize(uHeights, 0));
  vec3 normal = heightfieldNormal(uHeights, vTexCoord, texel, uSpacing, uExaggeration);
  float trueHeight = sampleSurface(vGrid);
  // Tinted by the map's height under the pixel, like a colour texture: the coarse geometry
  // must not move coastlines and snow lines.
  vec3 lit = shadeTerrain(trueHeight, normal, vRelativePosition);
  float errorM = (abs(vHeight - trueHeight) + uMapErrorM) * uExaggeration;
  fragColour = vec4(applyShadingMode(lit, 0, errorM, vRelativePosition), 1.0);
}
