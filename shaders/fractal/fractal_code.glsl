// The fractal code's per-cell parameters (render/fractal_gpu_decoder.hpp packs them; the CPU
// reference is tiles/fractal_code.cpp, whose integer arithmetic these shaders repeat exactly).
// One texel per smallest-range cell holds the parameters of the range that covers the cell:
//   x: range x | range y << 16      y: domain x | domain y << 16
//   z: size log2 | isometry << 4 | (scale index + 15) << 8
//   w: range mean, working units (height steps above the tile base * 16)
const int kScaleBits = 4;
const uint kMaxWorking = 16777215u;  // (2^20 - 1) * 16 + 15

struct RangeParams {
  ivec2 origin;
  ivec2 domain;
  int sizeLog2;
  int isometry;
  int scale;
  uint mean;
};

RangeParams unpackRange(uvec4 p) {
  RangeParams r;
  r.origin = ivec2(p.x & 0xffffu, p.x >> 16);
  r.domain = ivec2(p.y & 0xffffu, p.y >> 16);
  r.sizeLog2 = int(p.z & 15u);
  r.isometry = int((p.z >> 4) & 7u);
  r.scale = int((p.z >> 8) & 31u) - 15;
  r.mean = p.w;
  return r;
}

// Where pixel (x, y) of an r x r range reads the shrunk domain under isometry k.
ivec2 isometryPosition(int k, ivec2 p, int r) {
  int a = (k & 1) != 0 ? r - 1 - p.x : p.x;
  int b = (k & 2) != 0 ? r - 1 - p.y : p.y;
  return (k & 4) != 0 ? ivec2(b, a) : ivec2(a, b);
}

// The decoder slots (array layers) of one dispatch: workgroup layer z works on slot uLayers[z].
const int kMaxBatch = 64;  // FractalGpuDecoder::kMaxBatch
uniform int uLayers[kMaxBatch];
int slotLayer() {
  return uLayers[gl_WorkGroupID.z];
}

// The 2x2 average (floor) of the working image at shrunk-domain position uv of slot `layer`.
// The including shader declares the image uWorking before the #include.
uint shrunkSample(ivec2 domain, ivec2 uv, int layer) {
  ivec2 p = domain + 2 * uv;
  uint sum = imageLoad(uWorking, ivec3(p, layer)).x +
             imageLoad(uWorking, ivec3(p + ivec2(1, 0), layer)).x +
             imageLoad(uWorking, ivec3(p + ivec2(0, 1), layer)).x +
             imageLoad(uWorking, ivec3(p + ivec2(1, 1), layer)).x;
  return sum >> 2;
}
