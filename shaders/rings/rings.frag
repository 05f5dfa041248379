#version 450 core
// Rings renderer shading: per-pixel normals from the patch's data tile (its texture-array
// layer), then the common terrain shading and the shading mode (LOD colours, screen-space
// error of the data tile's level).
#include "common/shading.glsl"
#include "common/heightfield.glsl"
#include "common/lod_colours.glsl"

uniform vec2 uSampleSpacing;  // level-0 metres between samples
uniform float uExaggeration;
uniform int uTileSize;
layout(binding = 0) uniform sampler2DArray uHeights;
// Per slot: the geometric error of its tile (TileStats::geometricErrorM), metres.
layout(std430, binding = 1) readonly buffer SlotErrors { float slotGeometricErrorM[]; };

in float vHeight;
in vec3 vRelativePosition;
in vec2 vSample;
flat in int vSlot;
flat in int vLevel;
flat in int vLod;
out vec4 fragColour;

void main() {
  float texels = float(uTileSize + 1);
  vec3 uvw = vec3((vSample + 0.5) / texels, float(vSlot));
  vec3 normal = heightfieldNormalArray(uHeights, uvw, vec2(1.0 / texels),
                                       uSampleSpacing * float(1 << vLevel), uExaggeration);
  vec3 lit = shadeTerrain(vHeight, normal, vRelativePosition);
  float errorM = slotGeometricErrorM[vSlot] * uExaggeration;
  fragColour = vec4(applyShadingMode(lit, vLod, errorM, vRelativePosition), 1.0);
}
