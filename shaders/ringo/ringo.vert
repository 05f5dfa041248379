#version 450 core
// RINGO's blocks (src/tellus/lod/ringo/ringo_block_mesh.hpp): static buffers, built once per
// block. Positions arrive as ECEF split into whole metres (integers) and the fraction, like the
// globe reference's (globe.vert): relative to the eye they are exact anywhere on Earth, and a
// point two blocks share gets the same bits in both. Per draw only the block's edges that abut
// a coarser ring: there its odd edge vertices take their collapsed positions (onto the coarser
// block's vertices: crack-free joins; ringoVertexEcef is this shader's CPU twin). After a change
// of depth, per matrix, the share of each vertex's morph delta still to go: the vertex is drawn
// that far along its ellipsoid normal towards the surface the previous matrix drew
// (lod/ringo/ringo_morph.hpp). Feeds globe/globe.frag like globe.vert.

uniform mat4 uViewProjection;  // eye-relative ECEF -> clip
uniform ivec3 uEyeWhole;       // the eye in ECEF, split like the vertices
uniform vec3 uEyeFraction;
uniform int uCoarserEdges;     // bits: 1 north, 2 east, 4 south, 8 west
uniform float uMorphRemaining;  // 1 on a new matrix's first frame ... 0 once morphed
uniform vec3 uSunEcef;         // unit, towards the sun

layout(location = 0) in ivec3 aWhole;
layout(location = 1) in vec3 aFraction;
layout(location = 2) in ivec3 aCollapsedWhole;
layout(location = 3) in vec3 aCollapsedFraction;
layout(location = 4) in vec3 aNormal;   // unit, ECEF
layout(location = 5) in float aHeight;  // above the geoid, metres (the tint)
layout(location = 6) in uint aEdges;
layout(location = 7) in float aMorphDelta;           // metres along the normal
layout(location = 8) in float aCollapsedMorphDelta;  // the same at the collapsed position

out vec3 vNormal;            // in the vertex's east-north-up frame
out vec3 vSun;               // the sun in the same frame
out float vHeight;
out vec3 vRelativePosition;  // eye-relative ECEF, metres
out vec3 vEcef;              // ECEF in float: enough for directions and haze

const float kA2 = 6378137.0 * 6378137.0;
const float kB2 = 6356752.314245 * 6356752.314245;

void main() {
  bool collapse = (int(aEdges) & uCoarserEdges) != 0;
  ivec3 whole = collapse ? aCollapsedWhole : aWhole;
  vec3 fraction = collapse ? aCollapsedFraction : aFraction;
  vec3 relative = vec3(whole - uEyeWhole) + (fraction - uEyeFraction);
  vec3 ecef = vec3(whole) + fraction;
  vec3 up = normalize(vec3(ecef.xy / kA2, ecef.z / kB2));
  float delta = collapse ? aCollapsedMorphDelta : aMorphDelta;
  relative += up * (delta * uMorphRemaining);
  ecef += up * (delta * uMorphRemaining);
  vec3 east = cross(vec3(0.0, 0.0, 1.0), up);
  east = length(east) > 1e-6 ? normalize(east) : vec3(0.0, 1.0, 0.0);
  vec3 north = cross(up, east);
  vNormal = vec3(dot(aNormal, east), dot(aNormal, north), dot(aNormal, up));
  vSun = vec3(dot(uSunEcef, east), dot(uSunEcef, north), dot(uSunEcef, up));
  vHeight = aHeight + delta * uMorphRemaining;
  vRelativePosition = relative;
  vEcef = ecef;
  gl_Position = uViewProjection * vec4(relative, 1.0);
}
