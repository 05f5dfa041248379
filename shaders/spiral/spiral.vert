#version 450 core
// The spiral globe (seed 001): one static spiral (src/tellus/lod/spiral/spiral_mesh.hpp), each
// vertex a unit direction and a radius (radians of arc round the focal point), wrapped here onto
// the chosen projection round the focal point under the camera, its height fetched from the
// height textures (the vertex texture fetch the seed could not do; the stack of windows of
// spiral_height_levels.hpp, whose spiralWindowHeight and spiralLevelDepthFor this shader mirrors).
// Positions are the focal point's offset plus (focal point - eye), formed in double on the CPU:
// eye-relative and exact to millimetres near the eye. Feeds spiral/spiral.frag (the Blue Marble
// cube maps) or globe/globe.frag (the tint): normal and sun in the vertex's east-north-up frame,
// lit as on the globe whatever the projection (the seed's rule).
#include "spiral/spiral_projection.glsl"

const int kMaxLevels = 24;

uniform mat4 uViewProjection;   // eye-relative ECEF -> clip
uniform vec3 uFocusMinusEye;    // the focal point on the ellipsoid minus the eye, ECEF metres
uniform vec3 uFocusEcef;        // the focal point on the ellipsoid, float (haze, drape)
uniform vec3 uFocusEast, uFocusNorth, uFocusUp;
uniform float uFocusSinLat, uFocusCosLat, uFocusPrimeVerticalM, uFocusMeridianM;
uniform int uProjection;        // 0 globe, 1 flat, 2 hyperbolic, 3 dome
uniform float uMinRadius, uMaxRadius;
uniform bool uCorrectRadius;    // the seed's square-root radius correction
uniform float uStepsPerRevolution;
uniform vec3 uSunEcef;

// Heights: RG = (metres above the ellipsoid, the geoid's undulation there).
uniform sampler2D uBaseHeights;       // the whole Earth at uBaseDepth, columns wrap
uniform vec2 uBaseFocal;              // the focal point in the base's samples (x east, y south)
uniform float uBaseStepRad;
uniform sampler2DArray uLevelHeights; // one window a depth uBaseDepth + 1 + i
uniform int uLevelCount;
uniform int uLevelLayer[kMaxLevels];  // the window's layer; -1: none yet
uniform vec2 uLevelFocal[kMaxLevels];
uniform float uLevelStepRad[kMaxLevels];
uniform int uBaseDepth;
uniform int uTileCells;

layout(location = 0) in vec3 aVertex;  // (sin spin, cos spin, radius)

out vec3 vNormal;            // in the vertex's east-north-up frame
out vec3 vSun;
out float vHeight;           // above the geoid (the tint)
out vec3 vRelativePosition;  // eye-relative, metres
out vec3 vEcef;              // float: directions, haze and drapes
out vec3 vUp;                // the sphere's normal (geodetic up), ECEF: the cube maps' lookup

int spiralLevelDepthFor(float spacingRad) {
  if (!(spacingRad > 0.0)) return uBaseDepth + uLevelCount;
  float wanted = ceil(log2(3.14159265 / (float(uTileCells) * spacingRad)));
  return int(clamp(wanted, float(uBaseDepth), float(uBaseDepth + uLevelCount)));
}

vec2 texelAt(int layer, ivec2 at, ivec2 size) {
  at = clamp(at, ivec2(0), size - 1);
  return layer < 0 ? texelFetch(uBaseHeights, at, 0).rg
                   : texelFetch(uLevelHeights, ivec3(at, layer), 0).rg;
}

// The bilinear surface at (x, y) in the layer's samples (spiralWindowHeight).
vec2 windowHeight(int layer, vec2 xy) {
  ivec2 size = layer < 0 ? textureSize(uBaseHeights, 0) : textureSize(uLevelHeights, 0).xy;
  if (layer < 0) {
    float around = float(size.x - 1);
    xy.x -= around * floor(xy.x / around);
  }
  xy = clamp(xy, vec2(0.0), vec2(size - 1));
  ivec2 at = min(ivec2(xy), size - 2);
  vec2 f = xy - vec2(at);
  vec2 top = mix(texelAt(layer, at, size), texelAt(layer, at + ivec2(1, 0), size), f.x);
  vec2 bottom = mix(texelAt(layer, at + ivec2(0, 1), size), texelAt(layer, at + ivec2(1, 1), size), f.x);
  return mix(top, bottom, f.y);
}

void main() {
  SpiralFocus focus = SpiralFocus(uFocusEast, uFocusNorth, uFocusUp, uFocusSinLat, uFocusCosLat,
                                  uFocusPrimeVerticalM, uFocusMeridianM);
  vec2 direction = aVertex.xy;
  float radius = spiralCorrectedRadius(aVertex.z, uMinRadius, uMaxRadius, uCorrectRadius);
  vec2 latLon = spiralLatLonOffset(direction, radius, focus);

  // The depth that resolves the spiral's spacing here, or the deepest coarser window holding it.
  int layer = -1;
  vec2 xy = uBaseFocal + vec2(latLon.y, -latLon.x) / uBaseStepRad;
  float stepRad = uBaseStepRad;
  for (int depth = spiralLevelDepthFor(radius * 6.2831853 / uStepsPerRevolution);
       depth > uBaseDepth; --depth) {
    int i = depth - uBaseDepth - 1;
    if (uLevelLayer[i] < 0) continue;
    vec2 at = uLevelFocal[i] + vec2(latLon.y, -latLon.x) / uLevelStepRad[i];
    ivec2 size = textureSize(uLevelHeights, 0).xy;
    if (all(greaterThanEqual(at, vec2(1.0))) && all(lessThanEqual(at, vec2(size - 2)))) {
      layer = uLevelLayer[i];
      xy = at;
      stepRad = uLevelStepRad[i];
      break;
    }
  }
  vec2 here = windowHeight(layer, xy);
  float height = here.x;  // true heights: globe renderers take no exaggeration

  // The slope from central differences over a sample, in the vertex's east-north frame.
  float cosLat = max(cos(asin(clamp(uFocusSinLat, -1.0, 1.0)) + latLon.x), 1e-3);
  float eastM = 2.0 * stepRad * uFocusPrimeVerticalM * cosLat;
  float northM = 2.0 * stepRad * uFocusMeridianM;
  float dEast = (windowHeight(layer, xy + vec2(1.0, 0.0)).x - windowHeight(layer, xy - vec2(1.0, 0.0)).x) / eastM;
  float dNorth = (windowHeight(layer, xy - vec2(0.0, 1.0)).x - windowHeight(layer, xy + vec2(0.0, 1.0)).x) / northM;
  vNormal = normalize(vec3(-dEast, -dNorth, 1.0));

  vec3 offset = spiralProjectedOffset(uProjection, direction, radius, latLon, height, focus);
  vec3 up = normalize(spiralNormal(direction, radius, focus));
  vec3 east = cross(vec3(0.0, 0.0, 1.0), up);
  east = length(east) > 1e-6 ? normalize(east) : vec3(0.0, 1.0, 0.0);
  vec3 north = cross(up, east);
  vSun = vec3(dot(uSunEcef, east), dot(uSunEcef, north), dot(uSunEcef, up));
  vUp = up;
  vHeight = here.x - here.y;
  vRelativePosition = uFocusMinusEye + offset;
  vEcef = uFocusEcef + offset;
  gl_Position = uViewProjection * vec4(vRelativePosition, 1.0);
}
