// The importance of a sketch sample (giw::importanceMap): distance, slope, how squarely the
// surface faces the eye, and the frustum. Needs giw_warp_common.glsl before it.

uniform vec2 uRegionMin, uStep;  // grid units: the sketch's first sample and its spacing
uniform vec2 uSpacing;           // metres a grid unit, x and y
uniform vec3 uCamera;            // world metres
uniform float uExaggeration, uNearM;
uniform float uSlopeWeight, uOutsideImportance;
uniform vec4 uPlanes[6];         // the camera-relative frustum

float importanceAt(ivec2 ij) {
  vec2 g = uRegionMin + vec2(ij) * uStep;
  vec2 p = g * uSpacing;  // metres
  float h = heightAtGrid(g) * uExaggeration;
  vec2 d = max(uStep, vec2(1.0));  // grid units: the sketch's own spacing, at least a sample
  float gx = (heightAtGrid(g + vec2(d.x, 0.0)) - heightAtGrid(g - vec2(d.x, 0.0))) * uExaggeration / (2.0 * d.x * uSpacing.x);
  float gy = (heightAtGrid(g + vec2(0.0, d.y)) - heightAtGrid(g - vec2(0.0, d.y))) * uExaggeration / (2.0 * d.y * uSpacing.y);
  vec3 normal = normalize(vec3(-gx, -gy, 1.0));
  vec3 relative = vec3(p - uCamera.xy, h - uCamera.z);  // from the eye
  float distance = max(uNearM, length(relative));
  float facing = abs(dot(normal, -relative / distance));
  float slope = sqrt(gx * gx + gy * gy);
  bool inside = true;
  for (int k = 0; k < 6; ++k) inside = inside && dot(uPlanes[k].xyz, relative) + uPlanes[k].w >= 0.0;
  float value = (inside ? 1.0 : uOutsideImportance) * (1.0 + uSlopeWeight * min(slope, 2.0)) * (0.25 + facing) / distance;
  return max(value, 1e-30);
}
