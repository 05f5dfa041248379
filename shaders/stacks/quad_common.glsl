// The quadrangulation pipeline's shared layout (seed 003, section 3.2): the compute shaders in
// this folder run the stages of src/tellus/stacks/quadrangulation.cpp (the CPU reference) under
// the same names, on a batch of nodes at once (gl_GlobalInvocationID.y or .z is the node).
// Buffers hold one block per batch node; see StackQuadPipelineGpu for the bindings' sizes.

struct QuantisedLayer {
  int bottom;      // 1/kSubCell of a cell above the base
  int top;
  uint channel;    // material channel 0..3
  uint padding;
};

struct StackVertex {
  vec4 position;   // world metres, w = the level that made it
  vec4 normal;     // outward unit normal, w = 0
  vec4 materials;  // normalised material weights
};

const int kSubCell = 256;

// A batch node (StackQuadPipelineGpu::NodeJob).
struct NodeInfo {
  ivec4 origin;  // xyz: the node's first sample in its level's samples, w: the level
  ivec4 stitch;  // xyz: the parent's first cell in the node's cells, w: the stitch mask (0: none)
  uvec4 dest;    // x: its first vertex, y: its first index in the output, z: its counters
};

// Every level's stacks: per column [first, end) of its layers in stackLayers (absolute
// indices: an edited column's layers may lie anywhere), columns of all levels concatenated.
layout(std430, binding = 0) readonly buffer StackRanges { uint stackRanges[]; };
layout(std430, binding = 1) readonly buffer StackLayers { QuantisedLayer stackLayers[]; };
layout(std430, binding = 2) readonly buffer Nodes { NodeInfo nodes[]; };

uniform int uNodeCells;    // n
uniform int uFilterRadius; // r
uniform int uRawSide;      // n + 3 + 2r
uniform int uSmoothSide;   // n + 3
uniform int uBatchCount;   // nodes in this dispatch
uniform ivec4 uLevelLayout[16];   // per level: first column, 0, width, height
uniform vec4 uLevelGeometry[16];  // per level: stack spacing, cell height, cell base (metres)
uniform int uCoarseRawSide;       // the coarser level's volume of a stitched node:
uniform int uCoarseSmoothSide;    // (n - 1) / 2 + 1 cells (stitched_quadrangulation.hpp)

int rawBlock() { return uRawSide * uRawSide * uRawSide; }  // samples per node in a volume buffer
int cellBlock() { return uNodeCells * uNodeCells * uNodeCells; }
int coarseBlock() { return uCoarseRawSide * uCoarseRawSide * uCoarseRawSide; }


// The cell rules (stacks/dual_contouring.hpp).
const ivec2 kCellEdges[12] = ivec2[12](ivec2(0, 1), ivec2(2, 3), ivec2(4, 5), ivec2(6, 7),
                                       ivec2(0, 2), ivec2(1, 3), ivec2(4, 6), ivec2(5, 7),
                                       ivec2(0, 4), ivec2(1, 5), ivec2(2, 6), ivec2(3, 7));

bool cornerInside(uint classification, int corner) { return ((classification >> corner) & 1u) != 0u; }
bool cellHasVertex(uint classification) { return classification != 0u && classification != 255u; }
ivec3 cornerOffset(int corner) { return ivec3(corner & 1, (corner >> 1) & 1, (corner >> 2) & 1); }

uint crossingAxes(uint classification) {
  bool inside0 = cornerInside(classification, 0);
  uint axes = 0u;
  if (cornerInside(classification, 1) != inside0) axes |= 1u;
  if (cornerInside(classification, 2) != inside0) axes |= 2u;
  if (cornerInside(classification, 4) != inside0) axes |= 4u;
  return axes;
}

// A cell's code (stacks/dual_contouring.hpp): classification, owned quads, vertex bit.
const uint kVertexBit = 1u << 11;
uint codeQuads(uint code) { return (code >> 8) & 7u; }
bool codeHasVertex(uint code) { return (code & kVertexBit) != 0u; }

uint ownedQuads(uint classification, ivec3 c, int n) {
  uint axes = crossingAxes(classification);
  if (!(c.x <= n - 2 && c.y >= 1 && c.z >= 1)) axes &= ~1u;
  if (!(c.x >= 1 && c.y <= n - 2 && c.z >= 1)) axes &= ~2u;
  if (!(c.x >= 1 && c.y >= 1 && c.z <= n - 2)) axes &= ~4u;
  return axes;
}

// Stitching (lod/stacks/stitched_quadrangulation.cpp, StitchGeometry): whether node-local cell
// c lies in one of the coarser selected neighbours of the stitch mask.
bool coarseCell(int node, ivec3 c) {
  uint mask = uint(nodes[node].stitch.w);
  int n = uNodeCells;
  while (mask != 0u) {
    int bit = findLSB(mask);
    mask &= mask - 1u;
    ivec3 d = ivec3(bit % 3 - 1, (bit / 3) % 3 - 1, bit / 9 - 1);
    ivec3 low = nodes[node].stitch.xyz + 2 * d * (n - 1);
    if (all(greaterThanEqual(c, low)) && all(lessThan(c, low + 2 * n))) return true;
  }
  return false;
}
bool coarseSample(int node, ivec3 s) {
  if (nodes[node].stitch.w == 0) return false;
  for (int k = 0; k < 8; ++k) {
    if (coarseCell(node, s - cornerOffset(k))) return true;
  }
  return false;
}
// Floor of half: node-local samples to the coarse volume's (node origins are even).
ivec3 halfDown(ivec3 v) { return ivec3(floor(vec3(v) * 0.5)); }
