#version 450 core
// One RAG refinement pass (seed 004, sections 4.2 and 5.1.2): each triangle is dropped when
// it is certainly outside the view (early clipping), otherwise its edges are decided and it is
// split into one to four triangles, captured by transform feedback for the next pass. The CPU
// twin is rag::refine() (src/tellus/lod/rag/); the cases and their emission order are those of
// rag::tessellate(): counter-clockwise, hypotenuse between the second and third vertex, and a
// fill triangle after each invisible T-vertex (rag_tessellation.hpp).
#include "rag/rag_common.glsl"

layout(triangles) in;
layout(triangle_strip, max_vertices = 15) out;

uniform int uEarlyClip;

in vec3 vGrid[];
out vec3 gGrid;  // captured

void emitTriangle(vec3 a, vec3 b, vec3 c) {
  gGrid = a;
  EmitVertex();
  gGrid = b;
  EmitVertex();
  gGrid = c;
  EmitVertex();
  EndPrimitive();
}

// rag::midpoint: the map's height, or with `surface` below 1 the interpolated height moved that
// far towards it (RefinementSettings::morphBand).
vec3 midpoint(vec3 a, vec3 b, bool fromMap, float surface) {
  precise vec3 m = (a + b) * 0.5;
  if (!fromMap) return m;
  float mapHeight = sampleMap(m.xy);
  precise float morphed = m.z + surface * (mapHeight - m.z);
  m.z = surface >= 1.0 ? mapHeight : morphed;
  return m;
}

// The triangles of a case other than 0 (rag::tessellate's order), early returns instead of a switch (the seed,
// section 5.1.2).
void emitCase(uint tess, vec3 v0, vec3 v1, vec3 v2, vec3 a, vec3 b, vec3 c) {
  if (tess == kEdge01) {
    emitTriangle(v0, a, v2);
    emitTriangle(a, v1, v2);
    return;
  }
  if (tess == kEdge02) {
    emitTriangle(v0, v1, c);
    emitTriangle(c, v1, v2);
    return;
  }
  if (tess == (kEdge01 | kEdge02)) {
    emitTriangle(v0, a, c);
    emitTriangle(a, v1, v2);
    emitTriangle(c, a, v2);
    return;
  }
  if (tess == kEdge12) {
    emitTriangle(b, v0, v1);
    emitTriangle(b, v2, v0);
    return;
  }
  if (tess == (kEdge12 | kEdge01)) {
    emitTriangle(a, b, v0);
    emitTriangle(a, v1, b);
    emitTriangle(b, v2, v0);
    return;
  }
  if (tess == (kEdge12 | kEdge02)) {
    emitTriangle(b, v0, v1);
    emitTriangle(c, b, v2);
    emitTriangle(c, v0, b);
    return;
  }
  emitTriangle(a, b, v0);
  emitTriangle(a, v1, b);
  emitTriangle(c, b, v2);
  emitTriangle(c, v0, b);
}

void main() {
  vec3 v0 = vGrid[0], v1 = vGrid[1], v2 = vGrid[2];
  if (uEarlyClip != 0 && isOutsideFrustum(v0, v1, v2)) return;
  vec3 surface;
  uint needed = neededEdges(v0, v1, v2, surface);
  uint tess = tessellationCase(needed);
  if (tess == 0u) {
    emitTriangle(v0, v1, v2);
    return;
  }
  vec3 a = midpoint(v0, v1, true, surface.x);
  vec3 b = midpoint(v1, v2, (needed & kEdge12) != 0u, surface.y);
  vec3 c = midpoint(v0, v2, true, surface.z);
  emitCase(tess, v0, v1, v2, a, b, c);
  // An invisible T-vertex: the fill triangle over the sliver rasterisation would leave.
  if ((tess & kEdge12) != 0u && (needed & kEdge12) == 0u && fillIsSafe(v1, v2)) {
    emitTriangle(v1, b, v2);
  }
}
