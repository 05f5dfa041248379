// RAG's edge decisions and early clipping (seed 004), shared by refine.geom; the GPU twin of
// src/tellus/lod/rag/rag_refinement.cpp, with the same names and the same float maths in the
// same order (`precise` forbids the compiler to fuse or reorder it). Vertices are (u, v, h):
// samples east of the western column, samples north of the southern row, metres.

uniform mat4 uClipFromRelative;  // camera-relative world -> clip (RefinementView)
uniform vec3 uCameraGrid;        // the camera in (u, v, h) units
uniform vec3 uGridScale;         // metres per unit: spacing x, spacing y, exaggeration
uniform vec2 uViewportPx;
uniform float uFocalPx;          // pixels per metre at one metre, face-on (RefinementView)
uniform float uNearM;
uniform float uFarM;
uniform float uMinHeightM;       // the height map's range, for conservative clipping
uniform float uMaxHeightM;
uniform int uVariant;            // 0 Oblique (rag), 1 RightAngled (rag-right)
uniform float uPixelEdge;        // Oblique: split at this midpoint error, pixels
uniform int uEdgeProbes;         // Oblique: 1 the midpoint, 3 its quarter points too
uniform float uHeightDifferenceM;  // RightAngled: split above this weighted difference
uniform float uDepthDetail;      // RightAngled: weight at the far plane, 0..1
uniform float uMorphBand;        // Oblique: a split midpoint reaches the map's height at
                                 // uPixelEdge (1 + band) px of error; 0: at once (the seed)
uniform int uMapSurface;         // 1: heights from the reference's triangles (rag::MapSampling)
uniform float uEdgeLengthPx;     // Oblique: split an edge this long on screen face-on; 0: never
layout(binding = 0) uniform sampler2D uHeights;  // R32F metres, row 0 north

const float kClipMargin = 1e-3;  // rag::kClipMargin
const uint kEdge01 = 1u;
const uint kEdge12 = 2u;
const uint kEdge02 = 4u;

float sampleNearest(vec2 uv) {
  ivec2 size = textureSize(uHeights, 0);
  int col = clamp(int(floor(uv.x + 0.5)), 0, size.x - 1);
  int rowFromSouth = clamp(int(floor(uv.y + 0.5)), 0, size.y - 1);
  return texelFetch(uHeights, ivec2(col, size.y - 1 - rowFromSouth), 0).r;
}

// rag::sampleSurface: the reference's triangles, each cell split south-west to north-east.
float sampleSurface(vec2 uv) {
  ivec2 size = textureSize(uHeights, 0);
  if (size.x < 2 || size.y < 2) return sampleNearest(uv);
  float col = clamp(uv.x, 0.0, float(size.x - 1));
  float rowFromSouth = clamp(uv.y, 0.0, float(size.y - 1));
  int c0 = min(int(floor(col)), size.x - 2);
  int s0 = min(int(floor(rowFromSouth)), size.y - 2);
  precise float fx = col - float(c0);
  precise float fy = rowFromSouth - float(s0);
  int north = size.y - 2 - s0, south = size.y - 1 - s0;  // texel rows, 0 north
  float sw = texelFetch(uHeights, ivec2(c0, south), 0).r;
  float se = texelFetch(uHeights, ivec2(c0 + 1, south), 0).r;
  float nw = texelFetch(uHeights, ivec2(c0, north), 0).r;
  float ne = texelFetch(uHeights, ivec2(c0 + 1, north), 0).r;
  precise float below = sw + (se - sw) * fx + (ne - se) * fy;
  precise float above = sw + (nw - sw) * fy + (ne - nw) * fx;
  return fy <= fx ? below : above;
}

float sampleMap(vec2 uv) { return uMapSurface != 0 ? sampleSurface(uv) : sampleNearest(uv); }

vec4 clipPosition(vec3 vertex) {
  precise vec3 relative = (vertex - uCameraGrid) * uGridScale;
  precise vec4 clip = uClipFromRelative * vec4(relative, 1.0);
  return clip;
}

vec2 toPixels(vec4 clip) {
  precise vec2 ndc = clip.xy / clip.w;
  precise vec2 pixels = (ndc * 0.5 + 0.5) * uViewportPx;
  return pixels;
}

// `surface`: for a split edge, how far its midpoint goes from the interpolated height towards the
// map's (rag::EdgeMeasure::surface).
bool edgeNeedsSplit(vec3 a0, vec3 b0, out float surface) {
  surface = 1.0;
  // The ends in a canonical order (by u, then v), as on the CPU.
  bool ordered = a0.x < b0.x || (a0.x == b0.x && a0.y < b0.y);
  vec3 a = ordered ? a0 : b0;
  vec3 b = ordered ? b0 : a0;
  // Nothing in between, but for a cell's north-west to south-east diagonal on the reference's
  // surface (rag::crossesReferenceDiagonal).
  bool crossesDiagonal = uMapSurface != 0 && b.x - a.x == 1.0 && a.y - b.y == 1.0;
  if (abs(a.x - b.x) <= 1.0 && abs(a.y - b.y) <= 1.0 && !crossesDiagonal) return false;
  if (uVariant == 0) {
    precise vec3 interpolated = (a + b) * 0.5;
    vec3 fromMap = vec3(interpolated.xy, sampleMap(interpolated.xy));
    vec4 ci = clipPosition(interpolated);
    vec4 cm = clipPosition(fromMap);
    if (ci.w <= uNearM || cm.w <= uNearM) return true;  // passes by the eye
    if (uEdgeLengthPx > 0.0) {  // long for its distance: split without probing
      precise vec3 span = (b - a) * uGridScale;
      precise vec3 toMidpoint = (interpolated - uCameraGrid) * uGridScale;
      precise float lengthPx = length(span) * uFocalPx / length(toMidpoint);
      if (lengthPx >= uEdgeLengthPx) return true;
    }
    precise float error = length(toPixels(cm) - toPixels(ci));
    for (int k = 1; k <= 3 && uEdgeProbes >= 3; k += 2) {  // the quarter points
      precise vec3 q = a + (b - a) * (0.25 * float(k));
      vec3 qm = vec3(q.xy, sampleMap(q.xy));
      vec4 cq = clipPosition(q);
      vec4 cqm = clipPosition(qm);
      if (cq.w > uNearM && cqm.w > uNearM) {
        precise float quarter = length(toPixels(cqm) - toPixels(cq));
        error = max(error, quarter);
      }
    }
    if (uMorphBand > 0.0) {
      precise float past = (error - uPixelEdge) / (uPixelEdge * uMorphBand);
      surface = clamp(past, 0.0, 1.0);
    }
    return error >= uPixelEdge;
  }
  float w = min(clipPosition(a).w, clipPosition(b).w);
  precise float depth = clamp((w - uNearM) / (uFarM - uNearM), 0.0, 1.0);
  precise float weight = uDepthDetail + (1.0 - uDepthDetail) * (1.0 - depth);
  precise float value = abs(a.z - b.z) * weight;
  return value > uHeightDifferenceM;
}

uint neededEdges(vec3 v0, vec3 v1, vec3 v2, out vec3 surface) {
  uint bits = 0u;
  if (edgeNeedsSplit(v0, v1, surface.x)) bits |= kEdge01;
  if (edgeNeedsSplit(v1, v2, surface.y)) bits |= kEdge12;
  if (edgeNeedsSplit(v0, v2, surface.z)) bits |= kEdge02;
  return bits;
}

uint tessellationCase(uint needed) {
  if (uVariant == 1 && (needed & (kEdge01 | kEdge02)) != 0u) needed |= kEdge12;
  return needed;
}

// A fill triangle over the edge a-b is emitted only when the edge lies in front of the near
// plane: clipped at the near plane, the rounding of a sliver that is a line in the world is
// magnified by the division by w into a visible triangle.
bool fillIsSafe(vec3 a, vec3 b) {
  return clipPosition(a).w > uNearM && clipPosition(b).w > uNearM;
}

// True when the prism over the triangle's (u, v) footprint, from the map's lowest to its
// highest height, lies outside one plane of the view volume (reversed-Z depth in [0, 1]).
bool isOutsideFrustum(vec3 v0, vec3 v1, vec3 v2) {
  // Per plane: are all six corners outside? x < -w, x > w, y < -w, y > w, z < 0, z > w.
  bool allOutside[6] = bool[6](true, true, true, true, true, true);
  vec3 corners[3] = vec3[3](v0, v1, v2);
  for (int i = 0; i < 3; ++i) {
    for (int k = 0; k < 2; ++k) {
      vec4 c = clipPosition(vec3(corners[i].xy, k == 0 ? uMinHeightM : uMaxHeightM));
      // A margin of kClipMargin * |w| keeps float rounding (here and in the reference's
      // different arithmetic) from dropping a triangle the rasteriser would still draw.
      float margin = kClipMargin * abs(c.w);
      allOutside[0] = allOutside[0] && c.x < -c.w - margin;
      allOutside[1] = allOutside[1] && c.x > c.w + margin;
      allOutside[2] = allOutside[2] && c.y < -c.w - margin;
      allOutside[3] = allOutside[3] && c.y > c.w + margin;
      allOutside[4] = allOutside[4] && c.z < -margin;
      allOutside[5] = allOutside[5] && c.z > c.w + margin;
    }
  }
  return allOutside[0] || allOutside[1] || allOutside[2] || allOutside[3] || allOutside[4] ||
         allOutside[5];
}
