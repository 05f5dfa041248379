#version 450
// GAMeR pass 1: every coarse vertex's depth tag (CoarseTerrain::depthTags): the smallest depth
// whose error, projected at the vertex's distance less half a cell diagonal, is within the
// target.
layout(local_size_x = 64) in;
#include "gamer/gamer_select_common.glsl"

uniform vec3 uCamera;       // world metres
uniform float uExaggeration;
uniform float uScale;       // exaggeration * pixels a radian
uniform float uNearM;
uniform float uRadiusM;     // half a coarse cell's diagonal, metres
uniform float uTargetPx;

void main() {
  uint v = gl_GlobalInvocationID.x;
  if (v >= uint((uCellsX + 1) * (uCellsY + 1))) return;
  vec4 p = points[v];
  vec3 relative = vec3(p.xy - uCamera.xy, p.z * uExaggeration - uCamera.z);
  float distance = max(uNearM, length(relative) - uRadiusM);
  uint depths = uint(uMaxDepth + 1);
  uint tag = uint(uMaxDepth);
  for (int d = 0; d < uMaxDepth; ++d) {
    if (vertexErrors[v * depths + uint(d)] * uScale / distance <= uTargetPx) {
      tag = uint(d);
      break;
    }
  }
  tags[v] = tag;
}
