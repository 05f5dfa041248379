#version 450 core
// Shading of a mesh built from the grid by a CPU, pattern or warping LOD (the renderers of
// render/drawing/grid_mesh_shading.hpp): lit from the height texture's normals and tinted by its heights (so coarse
// triangles do not move coastlines); in the screen-space error mode the error is the vertical
// distance from the drawn surface to the texture's surface under the pixel, plus the texture's
// own error when it is a coarser level, projected at the pixel's distance; in the
// level-of-detail mode the tint is the vertex shader's level (vLevel).
#include "common/shading.glsl"
#include "common/heightfield.glsl"
#include "common/lod_colours.glsl"

uniform vec2 uSpacing;       // metres between height-texture samples
uniform float uExaggeration;
uniform float uMapErrorM;    // the height texture's own geometric error, metres
layout(binding = 0) uniform sampler2D uHeights;

in vec2 vTexCoord;
in float vHeight;
in vec3 vRelativePosition;
flat in int vLevel;
out vec4 fragColour;

void main() {
  vec2 texel = 1.0 / vec2(textureSize(uHeights, 0));
  vec3 normal = heightfieldNormal(uHeights, vTexCoord, texel, uSpacing, uExaggeration);
  float trueHeight = texture(uHeights, vTexCoord).r;
  vec3 lit = shadeTerrain(trueHeight, normal, vRelativePosition);
  float errorM = (abs(vHeight - trueHeight) + uMapErrorM) * uExaggeration;
  fragColour = vec4(applyShadingMode(lit, vLevel, errorM, vRelativePosition), 1.0);
}
