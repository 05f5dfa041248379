// GAMeR's selection on the GPU (render/gamer/gamer_gpu_selection.hpp), the buffers and values its
// two passes share. The CPU reference is lod/gamer/gamer_refinement.cpp (depthTags, select), which
// these passes follow step for step.

// Per coarse vertex (row by row from the south, (cellsX + 1) a row): world metres x, y and the
// unexaggerated height.
layout(std430, binding = 0) readonly buffer Points { vec4 points[]; };
// Per coarse vertex, maxDepth + 1 errors (metres): the largest of its cells' at each depth.
layout(std430, binding = 1) readonly buffer Errors { float vertexErrors[]; };
// Cell work groups finished in the running classification; its last group sets it back to 0.
layout(std430, binding = 2) coherent buffer GroupsDone { uint groupsDone; };
// Per cell (row by row from the south): its lowest and highest height, metres.
layout(std430, binding = 3) readonly buffer CellHeights { vec2 cellHeights[]; };
// Per pattern (PatternPool::patternIndex): its index count and first index.
layout(std430, binding = 4) readonly buffer Patterns { uvec2 patterns[]; };
// Per pattern, the coarse triangles that chose it this frame (coherent: the last group reads
// every group's counts; it leaves them at 0 for the next frame).
layout(std430, binding = 5) coherent buffer Counts { uint counts[]; };
// Per coarse triangle (2 a cell): pattern (0xffffffff: culled), its rank among the pattern's,
// and the instance (x | y << 16, half | interior depth << 8, D0 | D1 << 16, D2: the edges' morph
// depths in 1 / 8192).
struct Chosen {
  uint pattern;
  uint rank;
  uvec4 instance;
};
layout(std430, binding = 6) buffer ChosenTriangles { Chosen chosen[]; };
struct DrawCommand {  // DrawElementsIndirectCommand
  uint count;
  uint instanceCount;
  uint firstIndex;
  uint baseVertex;
  uint baseInstance;
};
layout(std430, binding = 7) buffer Commands { DrawCommand commands[]; };
layout(std430, binding = 8) writeonly buffer Instances { uvec4 instances[]; };
// x: coarse triangles drawn, y: refined triangles, z: patterns in use.
layout(std430, binding = 9) buffer Stats { uvec4 stats; };

uniform int uMaxDepth;
uniform int uCellsX, uCellsY;
uniform int uPatternCount;

uint vertexIndex(int i, int j) { return uint(j * (uCellsX + 1) + i); }
