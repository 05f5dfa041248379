#version 450
// GIW pass 4: every vertex of the warped geometry image (buildGeometryImage): its warped sketch
// position (between the two rows its output row falls between), its place and height on the
// grid, and the LOD tint's level from the warped cell's density.
layout(local_size_x = 8, local_size_y = 8) in;
#include "giw/giw_warp_common.glsl"

uniform vec4 uRegion;  // grid units: xy the sketch's first sample, zw its spacing

vec2 warped(int i, int k) {
  float t = columnT[k];
  int j = min(int(t), uSize - 2);
  float f = t - float(j);
  float a = rowX[j * uSize + i], b = rowX[(j + 1) * uSize + i];
  return vec2(a + (b - a) * f, t);
}

void main() {
  ivec2 ik = ivec2(gl_GlobalInvocationID.xy);
  int i = ik.x, k = ik.y;
  if (i >= uSize || k >= uSize) return;
  vec2 w = warped(i, k);
  vec2 g = uRegion.xy + w * uRegion.zw;
  // Density: the even cell's area over the warped cell's (from the neighbouring vertices).
  int i1 = min(i + 1, uSize - 1), i0 = i1 - 1, k1 = min(k + 1, uSize - 1), k0 = k1 - 1;
  vec2 du = warped(i1, k) - warped(i0, k);
  vec2 dv = warped(i, k1) - warped(i, k0);
  float area = abs(du.x * dv.y - du.y * dv.x);
  float density = area > 0.0 ? 1.0 / area : 1.0;
  float level = clamp(round(log2(max(density, 1.0)) * 0.5), 0.0, 7.0);
  vertices[k * uSize + i] = vec4(g, heightAtGrid(g), level);
}
