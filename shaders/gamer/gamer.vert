#version 450 core
// GAMeR: one vertex of an adaptive refinement pattern laid on one coarse triangle. The pattern's
// vertex is a lattice point (a, b) of the pool: barycentric weights (a, b, N - a - b) / N on the
// coarse triangle's corners (0, 1, 2); the instance names the coarse triangle (cell, half), its
// pattern's interior depth and its three edges' morph depths. Positions are in grid units: x
// samples east of the western column, y samples north of the southern row.
//
// Height: the geomorph of CoarseTerrain::morphedHeight (the CPU reference, step for step). The
// vertex's morph depth D is its edge's on an edge, the three blended inside (each weighing most
// near its edge); its height
// is the uniform depth-floor(D) sampling of the coarse triangle at the vertex, blended towards the
// depth-floor(D) + 1 sampling by D's fraction. A sampling reads the grid (bilinear between
// samples, exactly the sample on one) at its own lattice points; on an edge it interpolates
// along the edge from the lexicographically smaller end, so the two triangles sharing an edge
// compute the same height for each of its vertices (no crack).

uniform mat4 uClipFromRelative;  // camera-relative world -> clip
uniform vec3 uCameraGrid;        // the camera in (x, y, h) grid units
uniform vec3 uGridScale;         // metres per unit: spacing x, spacing y, exaggeration
uniform int uLatticeSteps;       // N = 2^maxDepth
uniform int uCellSide;           // coarse cell side, samples (2^maxDepth)
uniform int uMaxDepth;
layout(binding = 0) uniform sampler2D uHeights;  // R32F metres, row 0 north: the whole grid

layout(location = 0) in uvec2 aLattice;   // (a, b)
layout(location = 1) in uvec4 aInstance;  // (x | y << 16, half | interior << 8, D0 | D1 << 16, D2)

out vec2 vTexCoord;
out float vHeight;
out vec3 vRelativePosition;
flat out int vLevel;

const float kMorphDepthScale = 8192.0;  // gamer::kMorphDepthScale

ivec2 gridSize() { return textureSize(uHeights, 0); }

ivec2 coarseVertex(ivec2 ij) { return min(ij * uCellSide, gridSize() - 1); }

float sampleAt(ivec2 p) { return texelFetch(uHeights, ivec2(p.x, gridSize().y - 1 - p.y), 0).r; }

// Bilinear between the four samples around p (the CPU reference's heightAtGrid); on a sample,
// that sample (the same value, one fetch: most lattice points of full cells are samples).
float heightAt(vec2 p) {
  ivec2 size = gridSize();
  p = clamp(p, vec2(0.0), vec2(size - 1));
  if (p == floor(p)) return sampleAt(ivec2(p));
  ivec2 p0 = min(ivec2(p), size - 2);
  vec2 f = p - vec2(p0);
  float south = sampleAt(p0) * (1.0 - f.x) + sampleAt(p0 + ivec2(1, 0)) * f.x;
  float north = sampleAt(p0 + ivec2(0, 1)) * (1.0 - f.x) + sampleAt(p0 + ivec2(1, 1)) * f.x;
  return south * (1.0 - f.y) + north * f.y;
}

ivec2 corner[3];  // the coarse triangle's corners, grid coordinates

// The grid at lattice point (a, b): exact in float (integers, then a power-of-two division).
float latticeHeight(int a, int b) {
  ivec2 sum = a * corner[0] + b * corner[1] + (uLatticeSteps - a - b) * corner[2];
  return heightAt(vec2(sum) / float(uLatticeSteps));
}

// The uniform sampling of depth `depth` at lattice point (a, b) (CPU: samplingHeight).
float samplingHeight(int depth, int a, int b) {
  int n = uLatticeSteps, step = n >> depth, cw = n - a - b;
  if (cw == 0 || a == 0 || b == 0) {
    // Edge 0 runs from corner 0 to 1 (c = 0), edge 1 from 1 to 2 (a = 0), edge 2 from 2 to 0.
    int edge = cw == 0 ? 0 : (a == 0 ? 1 : 2);
    ivec2 from = corner[edge], to = corner[(edge + 1) % 3];
    int j = edge == 0 ? b : (edge == 1 ? cw : a);
    if (to.x < from.x || (to.x == from.x && to.y < from.y)) {
      ivec2 swap = from;
      from = to;
      to = swap;
      j = n - j;
    }
    int offset = j % step;
    int j0 = j - offset;
    float h0 = heightAt(vec2(from * n + (to - from) * j0) / float(n));
    if (offset == 0) return h0;
    float h1 = heightAt(vec2(from * n + (to - from) * (j0 + step)) / float(n));
    return h0 + (h1 - h0) * (float(offset) / float(step));
  }
  int a0 = a - a % step, b0 = b - b % step;
  if (a0 == a && b0 == b) return latticeHeight(a, b);
  float u = float(a - a0) / float(step), v = float(b - b0) / float(step);
  if (u + v <= 1.0) {
    return latticeHeight(a0, b0) * (1.0 - u - v) + latticeHeight(a0 + step, b0) * u + latticeHeight(a0, b0 + step) * v;
  }
  return latticeHeight(a0 + step, b0 + step) * (u + v - 1.0) + latticeHeight(a0 + step, b0) * (1.0 - v) +
         latticeHeight(a0, b0 + step) * (1.0 - u);
}

void main() {
  ivec2 cell = ivec2(int(aInstance.x & 0xffffu), int(aInstance.x >> 16));
  bool upper = (aInstance.y & 0xffu) != 0u;
  vLevel = int((aInstance.y >> 8) & 0xffu);
  ivec2 sw = coarseVertex(cell), ne = coarseVertex(cell + 1);
  // Corner 1 is the right angle: (SW, SE, NE) below the diagonal, (NE, NW, SW) above it.
  corner[0] = upper ? ne : sw;
  corner[1] = upper ? ivec2(sw.x, ne.y) : ivec2(ne.x, sw.y);
  corner[2] = upper ? sw : ne;
  int a = int(aLattice.x), b = int(aLattice.y), cw = uLatticeSteps - a - b;
  ivec2 sum = a * corner[0] + b * corner[1] + cw * corner[2];
  vec2 p = vec2(sum) / float(uLatticeSteps);

  float d0 = float(aInstance.z & 0xffffu) / kMorphDepthScale, d1 = float(aInstance.z >> 16) / kMorphDepthScale;
  float d2 = float(aInstance.w) / kMorphDepthScale;
  float ab = float(a * b), bc = float(b * cw), ca = float(cw * a);
  float depth = cw == 0 ? d0 : (a == 0 ? d1 : (b == 0 ? d2 : (d0 * ab + d1 * bc + d2 * ca) / (ab + bc + ca)));
  int lower = min(int(depth), uMaxDepth);
  float fraction = lower == uMaxDepth ? 0.0 : depth - float(lower);
  float h = samplingHeight(lower, a, b);
  if (fraction != 0.0) {
    float fine = samplingHeight(lower + 1, a, b);
    h = h + (fine - h) * fraction;
  }

  vec2 size = vec2(gridSize());
  vTexCoord = vec2(p.x + 0.5, size.y - 0.5 - p.y) / size;
  vHeight = h;
  vRelativePosition = (vec3(p, h) - uCameraGrid) * uGridScale;
  gl_Position = uClipFromRelative * vec4(vRelativePosition, 1.0);
}
