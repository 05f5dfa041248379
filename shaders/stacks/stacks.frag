#version 450 core
// Stack terrain: each material's colour weighted by the vertex's material weights, lit by the
// sun and the sky like the heightfield renderers (common/shading.glsl), faded into the haze.
// With imagery (common/imagery.glsl), the orthophoto covers the tops that meet the sky.
#include "common/shading.glsl"
#include "common/lod_colours.glsl"
#include "stacks/sky_heights.glsl"

in vec3 vRelativePosition;
in vec3 vNormal;
in vec4 vMaterials;
flat in int vLevel;
in float vErrorM;
out vec4 fragColour;

uniform vec3 uCameraPosition;  // world metres (z exaggerated, as vRelativePosition)
uniform float uExaggeration;   // vertical scale

// Linear RGB of the material channels: rock, soil, grass, anything else.
const vec3 kMaterialColours[4] = vec3[4](vec3(0.30, 0.27, 0.24), vec3(0.34, 0.22, 0.12),
                                         vec3(0.16, 0.30, 0.08), vec3(0.55, 0.55, 0.55));

void main() {
  vec4 w = vMaterials / max(dot(vMaterials, vec4(1.0)), 1e-6);
  vec3 albedo = w.x * kMaterialColours[0] + w.y * kMaterialColours[1] +
                w.z * kMaterialColours[2] + w.w * kMaterialColours[3];
  vec3 normal = normalize(vNormal);  // back faces are culled: only the outside is seen
  if (uImageryLayerCount > 0) {
    vec4 imagery = imageryColour(vRelativePosition.xy);  // every pixel: its derivatives and feedback
    float e = max(uExaggeration, 1e-3);
    vec3 world = vRelativePosition + uCameraPosition;
    world.z /= e;
    vec3 trueNormal = normalize(vec3(normal.xy, normal.z * e));
    albedo = drapeImagery(albedo, imagery * stackSkyExposure(world, trueNormal, vErrorM / e));
  }
  vec3 lit = shadeAlbedoWithSun(albedo, normal, uSunDirection, vRelativePosition);
  // The level of the MipMap that made the vertex (0 and no error for stacks-full).
  fragColour = vec4(applyShadingMode(lit, vLevel, vErrorM, vRelativePosition), 1.0);
}
