#version 450
// GAMeR pass 1 of 2, an invocation a coarse cell: the cell against the frustum, its corners'
// depth tags (CoarseTerrain::depthTags: the smallest depth whose error, projected at the vertex's
// distance less half a cell diagonal, is within the target) and morph depths, then each of its
// two triangles' pattern and edge morph depths (CoarseTerrain::select); a triangle takes its rank among the
// pattern's users with one atomic add. The last work group to finish then makes each pattern's
// run of instances (a prefix sum of the counts, in pattern order like the CPU's), its indirect
// draw command and the frame's totals.
layout(local_size_x = 64) in;
#include "gamer/gamer_select_common.glsl"

// Set every frame (few uniforms: each glProgramUniform call costs the render thread).
uniform vec4 uEye;          // xyz: the camera, world metres; w: the vertical exaggeration
uniform vec2 uProjection;   // x: exaggeration * pixels a radian; y: the near distance, metres
uniform vec4 uPlanes[6];    // the camera-relative frustum (Frustum::planes)
// Set when they change.
uniform float uRadiusM;     // half a coarse cell's diagonal, metres
uniform float uTargetPx;
uniform float uMorphBand;   // GamerSettings::morphBand (0: no geomorph)
uniform int uCulling;

const float kMorphDepthScale = 8192.0;  // gamer::kMorphDepthScale

shared bool lastGroup;

bool inFrustum(vec3 lo, vec3 hi) {
  for (int k = 0; k < 6; ++k) {
    vec4 plane = uPlanes[k];
    vec3 positive = vec3(plane.x >= 0.0 ? hi.x : lo.x, plane.y >= 0.0 ? hi.y : lo.y,
                         plane.z >= 0.0 ? hi.z : lo.z);
    if (dot(plane.xyz, positive) + plane.w < 0.0) return false;
  }
  return true;
}

// A coarse vertex's depth tag and its morph depth in the instances' fixed point (each of its
// cells computes them: no pass, no buffer between; CoarseTerrain::depthTags, morphDepthAt).
int depthTag(uint v, out uint morphDepth) {
  vec4 p = points[v];
  vec3 relative = vec3(p.xy - uEye.xy, p.z * uEye.w - uEye.z);
  float distance = max(uProjection.y, length(relative) - uRadiusM);
  uint depths = uint(uMaxDepth + 1);
  int tag = uMaxDepth;
  for (int d = 0; d < uMaxDepth; ++d) {
    if (vertexErrors[v * depths + uint(d)] * uProjection.x / distance <= uTargetPx) {
      tag = d;
      break;
    }
  }
  float depth = uMorphBand > 0.0 ? float(tag) : float(uMaxDepth);  // no geomorph: own samples
  if (tag > 0 && uMorphBand > 0.0) {
    // Depth d meets the target beyond error[d] * scale / target metres.
    // From the tag beyond that distance: depths of equal error are skipped together.
    int coarser = tag - 1;
    while (coarser > 0 && vertexErrors[v * depths + uint(coarser - 1)] == vertexErrors[v * depths + uint(coarser)]) --coarser;
    float coarserFrom = vertexErrors[v * depths + uint(tag - 1)] * uProjection.x / uTargetPx;
    float tagFrom = vertexErrors[v * depths + uint(tag)] * uProjection.x / uTargetPx;
    float span = uMorphBand * (coarserFrom - tagFrom);
    if (span > 0.0) depth = float(coarser) + float(tag - coarser) * clamp((coarserFrom - distance) / span, 0.0, 1.0);
  }
  morphDepth = uint(round(depth * kMorphDepthScale));
  return tag;
}

void classifyCell(uint cell) {
  int cx = int(cell % uint(uCellsX)), cy = int(cell / uint(uCellsX));
  if (uCulling != 0) {
    vec2 heights = cellHeights[cell] * uEye.w;
    vec3 lo = vec3(points[vertexIndex(cx, cy)].xy - uEye.xy, heights.x - uEye.z);
    vec3 hi = vec3(points[vertexIndex(cx + 1, cy + 1)].xy - uEye.xy, heights.y - uEye.z);
    if (!inFrustum(lo, hi)) {
      chosen[2u * cell].pattern = 0xffffffffu;
      chosen[2u * cell + 1u].pattern = 0xffffffffu;
      return;
    }
  }
  uint msw, mse, mne, mnw;
  int sw = depthTag(vertexIndex(cx, cy), msw), se = depthTag(vertexIndex(cx + 1, cy), mse);
  int ne = depthTag(vertexIndex(cx + 1, cy + 1), mne), nw = depthTag(vertexIndex(cx, cy + 1), mnw);
  int n = uMaxDepth + 1;
  for (int half_ = 0; half_ < 2; ++half_) {
    // Corner 1 is the right angle in both halves: (SW, SE, NE) and (NE, NW, SW).
    int c0 = half_ == 0 ? sw : ne, c1 = half_ == 0 ? se : nw, c2 = half_ == 0 ? ne : sw;
    uint m0 = half_ == 0 ? msw : mne, m1 = half_ == 0 ? mse : mnw, m2 = half_ == 0 ? mne : msw;
    int d0 = max(c0, c1), d1 = max(c1, c2), d2 = max(c2, c0);
    int interior = min(d0, min(d1, d2));
    uint pattern = uint((d0 * n + d1) * n + d2);
    uint rank = atomicAdd(counts[pattern], 1u);
    chosen[2u * cell + uint(half_)] =
        Chosen(pattern, rank, uvec4(uint(cx) | (uint(cy) << 16), uint(half_) | (uint(interior) << 8),
                                    max(m0, m1) | (max(m1, m2) << 16), max(m2, m0)));
  }
}

// Each pattern's run of instances and its draw command, the totals; the counts back to 0.
void writeCommands() {
  uint next = 0u, triangles = 0u, used = 0u;
  for (int p = 0; p < uPatternCount; ++p) {
    uint count = counts[p];
    uvec2 pattern = patterns[p];
    commands[p] = DrawCommand(pattern.x, count, pattern.y, 0u, next);
    next += count;
    triangles += count * (pattern.x / 3u);
    used += count > 0u ? 1u : 0u;
    counts[p] = 0u;
  }
  stats = uvec4(next, triangles, used, 0u);
}

void main() {
  uint cell = gl_GlobalInvocationID.x;
  if (cell < uint(uCellsX * uCellsY)) classifyCell(cell);
  memoryBarrierBuffer();  // this group's counts reach memory before it counts as done
  barrier();
  if (gl_LocalInvocationIndex == 0u) lastGroup = atomicAdd(groupsDone, 1u) == gl_NumWorkGroups.x - 1u;
  barrier();
  if (lastGroup && gl_LocalInvocationIndex == 0u) {
    memoryBarrierBuffer();
    writeCommands();
    groupsDone = 0u;
  }
}
