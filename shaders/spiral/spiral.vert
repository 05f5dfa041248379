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
#include "spiral/spiral_heights.glsl"

uniform mat4 uViewProjection;   // eye-relative ECEF -> clip
uniform vec3 uFocusMinusEye;    // the focal point on the ellipsoid minus the eye, ECEF metres
uniform vec3 uFocusEcef;        // the focal point on the ellipsoid, float (haze, drape)
uniform vec3 uFocusEast, uFocusNorth, uFocusUp;
uniform float uFocusSinLat, uFocusCosLat, uFocusPrimeVerticalM, uFocusMeridianM;
uniform int uProjection;        // 0 globe, 1 flat, 2 hyperbolic, 3 dome
uniform float uMinRadius, uMaxRadius;
uniform bool uCorrectRadius;    // the seed's square-root radius correction
uniform vec3 uSunEcef;

layout(location = 0) in vec3 aVertex;  // (sin spin, cos spin, radius)

out vec3 vNormal;            // in the vertex's east-north-up frame
out vec3 vSun;
out float vHeight;           // above the geoid (the tint)
out vec3 vRelativePosition;  // eye-relative, metres
out vec3 vEcef;              // float: directions, haze and drapes
out vec3 vUp;                // the sphere's normal (geodetic up), ECEF: the cube maps' lookup

// (d height / d east, d height / d north) at `at`: central differences over one of its samples.
vec2 slopeAt(SpiralHeightAt at, float cosLat) {
  float eastM = 2.0 * at.stepRad * uFocusPrimeVerticalM * cosLat;
  float northM = 2.0 * at.stepRad * uFocusMeridianM;
  float dEast = (windowHeight(at.layer, at.xy + vec2(1.0, 0.0)).x -
                 windowHeight(at.layer, at.xy - vec2(1.0, 0.0)).x) / eastM;
  float dNorth = (windowHeight(at.layer, at.xy - vec2(0.0, 1.0)).x -
                  windowHeight(at.layer, at.xy + vec2(0.0, 1.0)).x) / northM;
  return vec2(dEast, dNorth);
}

void main() {
  SpiralFocus focus = SpiralFocus(uFocusEast, uFocusNorth, uFocusUp, uFocusSinLat, uFocusCosLat,
                                  uFocusPrimeVerticalM, uFocusMeridianM);
  vec2 direction = aVertex.xy;
  float radius = spiralCorrectedRadius(aVertex.z, uMinRadius, uMaxRadius, uCorrectRadius);
  vec2 latLon = spiralLatLonOffset(direction, radius, focus);

  SpiralBlend blend = spiralBlendAt(latLon, radius);
  vec2 here = spiralBlendedHeight(blend);
  float height = here.x;  // true heights: globe renderers take no exaggeration

  // The slope from central differences over a sample of each place, blended alike, in the
  // vertex's east-north frame.
  float cosLat = max(cos(asin(clamp(uFocusSinLat, -1.0, 1.0)) + latLon.x), 1e-3);
  vec2 slope = slopeAt(blend.finer, cosLat);
  if (blend.share > 0.0) slope += (slopeAt(blend.coarser, cosLat) - slope) * blend.share;
  vNormal = normalize(vec3(-slope, 1.0));

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
