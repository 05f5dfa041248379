#version 450 core
// The globe reference: every sample of a latitude/longitude grid as a vertex on the WGS84
// ellipsoid (src/tellus/lod/globe/globe_mesh.hpp). Positions arrive as ECEF split into whole
// metres (integers) and the fraction; subtracting the eye's split the same way, the whole parts
// exactly in integers, keeps sub-millimetre precision anywhere on Earth ("relative to eye"),
// and a vertex shared by two chunks gives the same bits in both.

uniform mat4 uViewProjection;  // eye-relative ECEF -> clip
uniform ivec3 uEyeWhole;       // the eye in ECEF, split like the vertices
uniform vec3 uEyeFraction;
uniform vec3 uSunEcef;         // unit, towards the sun

layout(location = 0) in ivec3 aWhole;
layout(location = 1) in vec3 aFraction;
layout(location = 2) in vec3 aNormal;  // in the vertex's east-north-up frame
layout(location = 3) in float aHeight;  // above the geoid, metres (the tint)

out vec3 vNormal;
out vec3 vSun;               // the sun in the same frame
out float vHeight;
out vec3 vRelativePosition;  // eye-relative ECEF, metres
out vec3 vEcef;              // ECEF in float (half-metre steps): enough to look up a drape

const float kA2 = 6378137.0 * 6378137.0;
const float kB2 = 6356752.314245 * 6356752.314245;

void main() {
  vec3 relative = vec3(aWhole - uEyeWhole) + (aFraction - uEyeFraction);
  vec3 ecef = vec3(aWhole) + aFraction;  // float: enough for a direction
  // The vertex's local frame: up is the ellipsoid normal, east horizontal.
  vec3 up = normalize(vec3(ecef.xy / kA2, ecef.z / kB2));
  vec3 east = cross(vec3(0.0, 0.0, 1.0), up);
  east = length(east) > 1e-6 ? normalize(east) : vec3(0.0, 1.0, 0.0);
  vec3 north = cross(up, east);
  vSun = vec3(dot(uSunEcef, east), dot(uSunEcef, north), dot(uSunEcef, up));
  vNormal = aNormal;
  vHeight = aHeight;
  vRelativePosition = relative;
  vEcef = ecef;
  gl_Position = uViewProjection * vec4(relative, 1.0);
}
