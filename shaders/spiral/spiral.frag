#version 450 core
// The spiral globe's shading (seed 001, "Lighting and Texture Composition" and its Appendix A),
// from the Blue Marble cube maps (src/tellus/dem/globe_texture_set.hpp), looked up by the
// sphere's normal: the colour map lit by the diffuse term of the bump-mapped normal, a Phong
// highlight masked by the water map, clouds (rotated over time) lit by the unperturbed normal,
// night lights where that normal faces away from the sun. Tellus also displaces the vertices
// (the seed could not), so the bump map perturbs the normal of the displaced surface. Each
// feature can be compiled out for the seed's Table 3 (SPIRAL_FEATURES bits, SpiralFeature;
// compile-time, as the seed removed code: a uniform switch leaves the code running on SIMD
// rasterisers such as llvmpipe), and SPIRAL_WHITE is the seed's 'white' shader.
#include "common/shading.glsl"
#include "common/lod_colours.glsl"
#include "globe/atmosphere.glsl"

const int kClouds = 1;
const int kNightLights = 2;
const int kTangentNormalize = 4;
const int kBumpMapping = 8;
const int kSpecular = 16;
const int kDiffuse = 32;

uniform samplerCube uSurface;  // sRGB colour, A water
uniform samplerCube uRelief;   // the bump map's normal, tangent, binormal weights; A altitude
uniform samplerCube uSky;      // R clouds, G night lights
uniform mat3 uCloudRotation;   // the clouds' drift about the axis
#ifndef SPIRAL_FEATURES
#define SPIRAL_FEATURES 63
#endif
uniform vec3 uSunEcef;
uniform bool uAtmosphere;

in vec3 vNormal;             // the displaced surface's, in the east-north-up frame
in vec3 vSun;
in float vHeight;
in vec3 vRelativePosition;
in vec3 vEcef;
in vec3 vUp;                 // the sphere's normal (the geodetic up), ECEF
out vec4 fragColour;

bool on(int feature) { return (SPIRAL_FEATURES & feature) != 0; }

void main() {
#ifdef SPIRAL_WHITE
  fragColour = vec4(1.0);  // the seed's 'white' shader: as little as possible
#else
  vec3 up = normalize(vUp);
  // The displaced surface's normal in ECEF; the seed's tangent (-y, x, 0) runs east.
  vec3 tangent = vec3(-up.y, up.x, 0.0);
  if (on(kTangentNormalize)) tangent = normalize(tangent);
  vec3 binormal = cross(up, tangent);
  vec3 surfaceNormal = normalize(vNormal.x * normalize(tangent) + vNormal.y * normalize(binormal) + vNormal.z * up);
  vec4 surface = texture(uSurface, up);
  vec3 normal = surfaceNormal;
  if (on(kBumpMapping)) {
    vec3 w = texture(uRelief, up).rgb * 2.0 - 1.0;
    normal = normalize(w.r * surfaceNormal + w.g * tangent + w.b * binormal);
  }
  vec3 toLight = uSunEcef;
  vec3 toEye = normalize(-vRelativePosition);
  vec3 albedo = surface.rgb;  // decoded from sRGB by the texture format
  if (uImageryLayerCount > 0) albedo = drapeImagery(albedo, imageryColour(imageryRelativeLonLat(vEcef)));
  vec3 colour = albedo;
  if (on(kDiffuse)) colour = albedo * clamp(dot(normal, toLight), 0.0, 1.0);
  if (on(kSpecular)) {
    float highlight = pow(max(dot(normal, normalize(toLight + toEye)), 0.0), 200.0);
    colour += vec3(0.9, 0.85, 0.75) * highlight * surface.a;
  }
  float sphereLight = clamp(dot(up, toLight), 0.0, 1.0);
  float clouds = on(kClouds) ? texture(uSky, uCloudRotation * up).r : 0.0;
  colour = mix(colour, vec3(sphereLight), clouds);
  if (on(kNightLights)) {
    float night = texture(uSky, up).g;
    colour += vec3(1.0, 0.82, 0.5) * night * night * (1.0 - clamp(sphereLight * 10.0, 0.0, 1.0)) * (1.0 - clouds);
  }
  if (uAtmosphere) {
    vec3 air = vec3(0.20, 0.34, 0.70) * smoothstep(-0.1, 0.3, dot(up, toLight));
    colour = mix(colour, air, atmosphericHaze(vRelativePosition, uEyeEcef));
  }
  fragColour = vec4(applyShadingMode(linearToSrgb(colour), 0, 0.0, vRelativePosition), 1.0);
#endif
}
