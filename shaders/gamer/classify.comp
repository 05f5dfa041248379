#version 450
// GAMeR pass 2: every coarse cell against the frustum, then each of its two triangles' pattern
// from its edge depths (CoarseTerrain::select); a triangle takes its rank among the pattern's
// users with one atomic add.
layout(local_size_x = 64) in;
#include "gamer/gamer_select_common.glsl"

uniform vec3 uCamera;  // world metres
uniform float uExaggeration;
uniform int uCulling;
uniform vec4 uPlanes[6];  // the camera-relative frustum (Frustum::planes)

bool inFrustum(vec3 lo, vec3 hi) {
  for (int k = 0; k < 6; ++k) {
    vec4 plane = uPlanes[k];
    vec3 positive = vec3(plane.x >= 0.0 ? hi.x : lo.x, plane.y >= 0.0 ? hi.y : lo.y,
                         plane.z >= 0.0 ? hi.z : lo.z);
    if (dot(plane.xyz, positive) + plane.w < 0.0) return false;
  }
  return true;
}

void main() {
  uint cell = gl_GlobalInvocationID.x;
  if (cell >= uint(uCellsX * uCellsY)) return;
  int cx = int(cell % uint(uCellsX)), cy = int(cell / uint(uCellsX));
  if (uCulling != 0) {
    vec2 heights = cellHeights[cell] * uExaggeration;
    vec3 lo = vec3(points[vertexIndex(cx, cy)].xy - uCamera.xy, heights.x - uCamera.z);
    vec3 hi = vec3(points[vertexIndex(cx + 1, cy + 1)].xy - uCamera.xy, heights.y - uCamera.z);
    if (!inFrustum(lo, hi)) {
      chosen[2u * cell] = uvec4(0xffffffffu);
      chosen[2u * cell + 1u] = uvec4(0xffffffffu);
      return;
    }
  }
  int sw = int(tags[vertexIndex(cx, cy)]), se = int(tags[vertexIndex(cx + 1, cy)]);
  int ne = int(tags[vertexIndex(cx + 1, cy + 1)]), nw = int(tags[vertexIndex(cx, cy + 1)]);
  int n = uMaxDepth + 1;
  for (int half_ = 0; half_ < 2; ++half_) {
    // Corner 1 is the right angle in both halves: (SW, SE, NE) and (NE, NW, SW).
    int c0 = half_ == 0 ? sw : ne, c1 = half_ == 0 ? se : nw, c2 = half_ == 0 ? ne : sw;
    int d0 = max(c0, c1), d1 = max(c1, c2), d2 = max(c2, c0);
    int interior = min(d0, min(d1, d2));
    uint pattern = uint((d0 * n + d1) * n + d2);
    uint rank = atomicAdd(counts[pattern], 1u);
    chosen[2u * cell + uint(half_)] = uvec4(pattern, rank, uint(cx) | (uint(cy) << 16),
                                            uint(half_) | (uint(interior) << 8));
  }
}
