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
  vec4 position;   // world metres, w = 1
  vec4 normal;     // outward unit normal, w = 0
  vec4 materials;  // normalised material weights
};

const int kSubCell = 256;

layout(std430, binding = 0) readonly buffer StackOffsets { uint stackOffsets[]; };
layout(std430, binding = 1) readonly buffer StackLayers { QuantisedLayer stackLayers[]; };
layout(std430, binding = 2) readonly buffer NodeOrigins { ivec4 nodeOrigins[]; };  // xyz: origin sample

uniform int uNodeCells;    // n
uniform int uFilterRadius; // r
uniform int uRawSide;      // n + 3 + 2r
uniform int uSmoothSide;   // n + 3
uniform int uBatchCount;   // nodes in this dispatch

int rawBlock() { return uRawSide * uRawSide * uRawSide; }  // samples per node in a volume buffer
int cellBlock() { return uNodeCells * uNodeCells * uNodeCells; }

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

uint ownedQuads(uint classification, ivec3 c, int n) {
  uint axes = crossingAxes(classification);
  if (!(c.x <= n - 2 && c.y >= 1 && c.z >= 1)) axes &= ~1u;
  if (!(c.x >= 1 && c.y <= n - 2 && c.z >= 1)) axes &= ~2u;
  if (!(c.x >= 1 && c.y >= 1 && c.z <= n - 2)) axes &= ~4u;
  return axes;
}
