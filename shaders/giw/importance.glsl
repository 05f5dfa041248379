// The importance of a sketch sample (giw::importanceMap): distance, slope, how squarely the
// surface faces the eye, and the frustum. Needs giw_warp_common.glsl before it.

// Set every frame (few uniforms: each glProgramUniform call costs the render thread).
uniform vec4 uRegion;     // grid units: xy the sketch's first sample, zw its spacing
uniform vec4 uEye;        // xyz: the camera, world metres; w: the vertical exaggeration
uniform float uNearM;
uniform vec4 uPlanes[6];  // the camera-relative frustum
// Set when they change.
uniform vec2 uSpacing;    // metres a grid unit, x and y
uniform float uSlopeWeight, uOutsideImportance;

float importanceAt(ivec2 ij) {
  vec2 g = uRegion.xy + vec2(ij) * uRegion.zw;
  vec2 p = g * uSpacing;  // metres
  float h = heightAtGrid(g) * uEye.w;
  vec2 d = max(uRegion.zw, vec2(1.0));  // grid units: the sketch's own spacing, at least a sample
  float gx = (heightAtGrid(g + vec2(d.x, 0.0)) - heightAtGrid(g - vec2(d.x, 0.0))) * uEye.w / (2.0 * d.x * uSpacing.x);
  float gy = (heightAtGrid(g + vec2(0.0, d.y)) - heightAtGrid(g - vec2(0.0, d.y))) * uEye.w / (2.0 * d.y * uSpacing.y);
  vec3 normal = normalize(vec3(-gx, -gy, 1.0));
  vec3 relative = vec3(p - uEye.xy, h - uEye.z);  // from the eye
  float distance = max(uNearM, length(relative));
  float facing = abs(dot(normal, -relative / distance));
  float slope = sqrt(gx * gx + gy * gy);
  bool inside = true;
  for (int k = 0; k < 6; ++k) inside = inside && dot(uPlanes[k].xyz, relative) + uPlanes[k].w >= 0.0;
  float value = (inside ? 1.0 : uOutsideImportance) * (1.0 + uSlopeWeight * min(slope, 2.0)) * (0.25 + facing) / distance;
  return max(value, 1e-30);
}
