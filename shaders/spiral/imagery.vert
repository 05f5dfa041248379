#version 450 core
// Imagery draped on the spiral globe (seed 001's second pass: decals and the texture quadtree):
// each node's quad tessellated into a grid whose vertices the CPU gives as the spiral's are
// given, a direction and a radius (radians of arc) from the focal point, formed in double from
// the vertex's latitude and longitude; so the same projection and the same height windows
// place them (spiral_projection.glsl, spiral_heights.glsl) and the drape lies on the spiral's
// surface. The drape is drawn a little nearer the eye (uPull, a fraction of the distance, the
// same on screen) so it wins the depth test against the terrain it covers, and loses it to
// terrain in front.
#include "spiral/spiral_projection.glsl"
#include "spiral/spiral_heights.glsl"

uniform mat4 uViewProjection;   // eye-relative ECEF -> clip
uniform vec3 uFocusMinusEye;    // the focal point on the ellipsoid minus the eye, ECEF metres
uniform vec3 uFocusEast, uFocusNorth, uFocusUp;
uniform float uFocusSinLat, uFocusCosLat, uFocusPrimeVerticalM, uFocusMeridianM;
uniform int uProjection;        // 0 globe, 1 flat, 2 hyperbolic, 3 dome
uniform float uPull;            // the drape's offset towards the eye, a fraction of the distance

layout(location = 0) in vec3 aVertex;  // (sin azimuth, cos azimuth, radius) from the focal point
layout(location = 1) in vec2 aTexel;   // texture coordinates in the node's texture

out vec2 vTexel;

void main() {
  SpiralFocus focus = SpiralFocus(uFocusEast, uFocusNorth, uFocusUp, uFocusSinLat, uFocusCosLat,
                                  uFocusPrimeVerticalM, uFocusMeridianM);
  vec2 direction = aVertex.xy;
  float radius = aVertex.z;
  vec2 latLon = spiralLatLonOffset(direction, radius, focus);
  float height = spiralBlendedHeight(spiralBlendAt(latLon, radius)).x;
  vec3 offset = spiralProjectedOffset(uProjection, direction, radius, latLon, height, focus);
  vec3 relative = (uFocusMinusEye + offset) * (1.0 - uPull);
  vTexel = aTexel;
  gl_Position = uViewProjection * vec4(relative, 1.0);
}
