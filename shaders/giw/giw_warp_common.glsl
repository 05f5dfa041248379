// Geometry image warping on the GPU (render/giw/giw_gpu_warp.hpp): the buffers and helpers its
// passes share. The CPU reference is lod/giw/giw_warp.cpp (importanceMap, warpRowsThenColumns,
// buildGeometryImage), which the passes follow step for step.

layout(binding = 0) uniform sampler2D uHeights;  // R32F metres, the whole grid, row 0 north

// size x size importance values, row-major, row 0 at the region's south edge (coherent: a row
// group's invocations write them, its first reads them).
layout(std430, binding = 0) coherent buffer Importance { float importance[]; };
// Per sketch row, its samples' warped x (sketch units); then per row its total importance
// (coherent: the last row's group reads every other group's).
layout(std430, binding = 1) buffer RowWarp { float rowX[]; };
layout(std430, binding = 2) coherent buffer RowTotals { float rowTotals[]; };
// Scratch for the running sums: size x size (one row each), then size (the columns').
layout(std430, binding = 3) buffer Cumulative { float cumulative[]; };
// Per output row, its sketch row coordinate (the one distribution of all columns).
layout(std430, binding = 4) buffer ColumnT { float columnT[]; };
// The warped geometry image: (x, y, height, level) a vertex in grid units and metres.
layout(std430, binding = 5) writeonly buffer Vertices { vec4 vertices[]; };

uniform int uSize;            // n, vertices a side
uniform float uUniformShare;

ivec2 gridSize() { return textureSize(uHeights, 0); }
float sampleAt(ivec2 p) { return texelFetch(uHeights, p, 0).r; }  // (column, row from the north)

// HeightGrid::heightAtWorld at grid units g (x east, y north of the southern row): bilinear
// between the four samples around it, clamped to the grid.
float heightAtGrid(vec2 g) {
  ivec2 size = gridSize();
  float col = clamp(g.x, 0.0, float(size.x - 1));
  float row = clamp(float(size.y - 1) - g.y, 0.0, float(size.y - 1));
  int c0 = min(int(col), max(size.x - 2, 0)), r0 = min(int(row), max(size.y - 2, 0));
  int c1 = min(c0 + 1, size.x - 1), r1 = min(r0 + 1, size.y - 1);
  float fx = col - float(c0), fy = row - float(r0);
  float top = sampleAt(ivec2(c0, r0)) * (1.0 - fx) + sampleAt(ivec2(c1, r0)) * fx;
  float bottom = sampleAt(ivec2(c0, r1)) * (1.0 - fx) + sampleAt(ivec2(c1, r1)) * fx;
  return top * (1.0 - fy) + bottom * fy;
}
