// Terrain shading shared by every renderer. CPU twin: src/tellus/render/shading/terrain_shading.cpp
// (same names, same maths); keep the two in step.
//
// Inputs: height (metres), unit normal in the world frame (x east, y north, z up), and the
// camera-relative position of the shaded point (metres). Output: display-ready sRGB.

#include "common/imagery.glsl"

const int kMaxRampStops = 16;
uniform int uRampStopCount;
uniform float uRampHeights[kMaxRampStops];  // metres, increasing
uniform vec3 uRampColours[kMaxRampStops];   // linear RGB
uniform vec3 uSunDirection;                 // unit, towards the sun
uniform vec3 uSunColour;
uniform vec3 uSkyColour;                    // ambient light from the sky (linear)
uniform vec3 uHazeColour;                   // colour distant terrain fades to (linear)
uniform float uHazeDensity;                 // per metre
uniform float uHazeStart;                   // metres from the camera where haze begins
uniform float uSlopeRock;                   // 0..1: how much steep slopes turn to rock

vec3 rampColour(float heightM) {
  if (heightM <= uRampHeights[0]) return uRampColours[0];
  for (int i = 1; i < uRampStopCount; ++i) {
    if (heightM <= uRampHeights[i]) {
      float t = (heightM - uRampHeights[i - 1]) / (uRampHeights[i] - uRampHeights[i - 1]);
      return mix(uRampColours[i - 1], uRampColours[i], t);
    }
  }
  return uRampColours[uRampStopCount - 1];
}

vec3 linearToSrgb(vec3 c) {
  c = clamp(c, 0.0, 1.0);
  return mix(c * 12.92, 1.055 * pow(c, vec3(1.0 / 2.4)) - 0.055, step(vec3(0.0031308), c));
}

// The same with the sun's direction given, in the frame of `normal` (the globe shades each
// point in its own east-north-up frame, where the sun's direction varies over the planet).
vec3 shadeTerrainWithSun(float heightM, vec3 normal, vec3 sunDirection, vec3 relativePosition);

// The flat renderers' shading: the tint, or the imagery over it where a virtual texture is bound
// (common/imagery.glsl, by the camera-relative world position).
vec3 terrainAlbedo(float heightM, vec3 normal);
vec3 shadeAlbedoWithSun(vec3 albedo, vec3 normal, vec3 sunDirection, vec3 relativePosition);
vec3 shadeTerrain(float heightM, vec3 normal, vec3 relativePosition) {
  vec3 albedo = terrainAlbedo(heightM, normal);
  if (uImageryLayerCount > 0) albedo = drapeImagery(albedo, imageryColour(relativePosition.xy));
  return shadeAlbedoWithSun(albedo, normal, uSunDirection, relativePosition);
}

// The hypsometric tint at a height, steep land turning to bare rock (linear RGB).
vec3 terrainAlbedo(float heightM, vec3 normal) {
  vec3 albedo = rampColour(heightM);
  float steepness = 1.0 - normal.z;
  float rock = uSlopeRock * smoothstep(0.25, 0.55, steepness) * step(0.5, heightM);
  return mix(albedo, vec3(0.26, 0.23, 0.20), rock);
}

// A surface colour (linear RGB: the tint, or a colour map draped over the globe) lit by the sun
// and the sky, linear RGB.
vec3 litAlbedo(vec3 albedo, vec3 normal, vec3 sunDirection) {
  float sun = max(dot(normal, sunDirection), 0.0);
  float skyVisibility = 0.5 + 0.5 * normal.z;
  return albedo * (uSunColour * sun + uSkyColour * skyVisibility);
}

// The same faded into the distance haze, display-ready sRGB.
vec3 shadeAlbedoWithSun(vec3 albedo, vec3 normal, vec3 sunDirection, vec3 relativePosition) {
  vec3 lit = litAlbedo(albedo, normal, sunDirection);
  float haze = 1.0 - exp(-max(length(relativePosition) - uHazeStart, 0.0) * uHazeDensity);
  return linearToSrgb(mix(lit, uHazeColour, haze));
}

vec3 shadeTerrainWithSun(float heightM, vec3 normal, vec3 sunDirection, vec3 relativePosition) {
  return shadeAlbedoWithSun(terrainAlbedo(heightM, normal), normal, sunDirection,
                            relativePosition);
}
