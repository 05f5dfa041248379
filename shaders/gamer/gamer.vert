#version 450 core
// GAMeR: one vertex of an adaptive refinement pattern laid on one coarse triangle. The pattern's
// vertex is a lattice point (a, b) of the pool: barycentric weights (a, b, N - a - b) / N on the
// coarse triangle's corners (0, 1, 2); the instance names the coarse triangle (cell, half) and
// its pattern's interior depth. Positions are in grid units: x samples east of the western
// column, y samples north of the southern row; heights are read from the grid texture at that
// point (bilinear between samples, exactly the sample on one), so two triangles that put a vertex
// at the same point agree on its height.

uniform mat4 uClipFromRelative;  // camera-relative world -> clip
uniform vec3 uCameraGrid;        // the camera in (x, y, h) grid units
uniform vec3 uGridScale;         // metres per unit: spacing x, spacing y, exaggeration
uniform int uLatticeSteps;       // N = 2^maxDepth
uniform int uCellSide;           // coarse cell side, samples (2^maxDepth)
layout(binding = 0) uniform sampler2D uHeights;  // R32F metres, row 0 north: the whole grid

layout(location = 0) in uvec2 aLattice;   // (a, b)
layout(location = 1) in uvec2 aInstance;  // (x | y << 16, half | interior depth << 8)

out vec2 vTexCoord;
out float vHeight;
out vec3 vRelativePosition;
flat out int vLevel;

ivec2 gridSize() { return textureSize(uHeights, 0); }

ivec2 coarseVertex(ivec2 ij) { return min(ij * uCellSide, gridSize() - 1); }

float sampleAt(ivec2 p) { return texelFetch(uHeights, ivec2(p.x, gridSize().y - 1 - p.y), 0).r; }

// Bilinear between the four samples around p (the CPU reference's heightAtGrid).
float heightAt(vec2 p) {
  ivec2 size = gridSize();
  p = clamp(p, vec2(0.0), vec2(size - 1));
  ivec2 p0 = min(ivec2(p), size - 2);
  vec2 f = p - vec2(p0);
  float south = sampleAt(p0) * (1.0 - f.x) + sampleAt(p0 + ivec2(1, 0)) * f.x;
  float north = sampleAt(p0 + ivec2(0, 1)) * (1.0 - f.x) + sampleAt(p0 + ivec2(1, 1)) * f.x;
  return south * (1.0 - f.y) + north * f.y;
}

void main() {
  ivec2 cell = ivec2(int(aInstance.x & 0xffffu), int(aInstance.x >> 16));
  bool upper = (aInstance.y & 0xffu) != 0u;
  vLevel = int(aInstance.y >> 8);
  ivec2 sw = coarseVertex(cell), ne = coarseVertex(cell + 1);
  // Corner 1 is the right angle: (SW, SE, NE) below the diagonal, (NE, NW, SW) above it.
  vec2 c0 = upper ? vec2(ne) : vec2(sw);
  vec2 c1 = upper ? vec2(sw.x, ne.y) : vec2(ne.x, sw.y);
  vec2 c2 = upper ? vec2(sw) : vec2(ne);
  vec3 w = vec3(float(aLattice.x), float(aLattice.y), float(uLatticeSteps - int(aLattice.x) - int(aLattice.y))) /
           float(uLatticeSteps);
  vec2 p = w.x * c0 + w.y * c1 + w.z * c2;
  float h = heightAt(p);
  vec2 size = vec2(gridSize());
  vTexCoord = vec2(p.x + 0.5, size.y - 0.5 - p.y) / size;
  vHeight = h;
  vRelativePosition = (vec3(p, h) - uCameraGrid) * uGridScale;
  gl_Position = uClipFromRelative * vec4(vRelativePosition, 1.0);
}
