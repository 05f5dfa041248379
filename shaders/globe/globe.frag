#version 450 core
// Shading of the globe reference: the hypsometric tint and sun light of the flat renderers, each
// point lit in its own east-north-up frame, or a colour map draped over the globe (Blue Marble)
// lit the same way; imagery (common/imagery.glsl, by longitude and latitude) over either. The reference draws every sample: its screen-space error is 0 (green in the
// error view).
#include "common/shading.glsl"
#include "common/lod_colours.glsl"
#include "globe/atmosphere.glsl"

uniform bool uAtmosphere;  // haze by the air the view ray crosses, not by distance
uniform bool uDrapeEnabled;
uniform sampler2D uDrape;  // sRGB texels, row 0 north
uniform vec4 uDrapeBox;    // west, north, east - west, south - north (degrees)

in vec3 vNormal;
in vec3 vSun;
in float vHeight;
in vec3 vRelativePosition;
in vec3 vEcef;
out vec4 fragColour;

const float kE2 = 0.00669437999014;  // WGS84 first eccentricity squared
const float kDegreesPerRadian = 57.29577951308232;

// The drape's colour at this fragment's latitude and longitude, linear RGB. Per fragment, so a
// triangle across the antimeridian does not smear the map; the mip level comes from whichever
// of u and u shifted by half the map varies smoothly here.
vec3 drapeAlbedo() {
  float lon = atan(vEcef.y, vEcef.x) * kDegreesPerRadian;
  float lat = atan(vEcef.z, (1.0 - kE2) * length(vEcef.xy)) * kDegreesPerRadian;
  vec2 uv = vec2((lon - uDrapeBox.x) / uDrapeBox.z, (lat - uDrapeBox.y) / uDrapeBox.w);
  vec2 shifted = vec2(fract(uv.x + 0.5), uv.y);
  vec2 dx = dFdx(uv), dy = dFdy(uv);
  vec2 dxShifted = dFdx(shifted), dyShifted = dFdy(shifted);
  if (abs(dxShifted.x) + abs(dyShifted.x) < abs(dx.x) + abs(dy.x)) {
    dx = dxShifted;
    dy = dyShifted;
  }
  vec3 srgb = textureGrad(uDrape, uv, dx, dy).rgb;
  return mix(srgb / 12.92, pow((srgb + 0.055) / 1.055, vec3(2.4)), step(vec3(0.04045), srgb));
}

void main() {
  vec3 normal = normalize(vNormal);
  vec3 sun = normalize(vSun);
  vec3 albedo = uDrapeEnabled ? drapeAlbedo() : terrainAlbedo(vHeight, normal);
  if (uImageryLayerCount > 0) albedo = drapeImagery(albedo, imageryColour(imageryRelativeLonLat(vEcef)));
  vec3 shaded;
  if (uAtmosphere) {
    vec3 air = vec3(0.20, 0.34, 0.70) * smoothstep(-0.1, 0.3, sun.z);  // dark on the night side
    shaded = linearToSrgb(mix(litAlbedo(albedo, normal, sun), air, atmosphericHaze(vRelativePosition, uEyeEcef)));
  } else {
    shaded = shadeAlbedoWithSun(albedo, normal, sun, vRelativePosition);
  }
  fragColour = vec4(applyShadingMode(shaded, 0, 0.0, vRelativePosition), 1.0);
}
