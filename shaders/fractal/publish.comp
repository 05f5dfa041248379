#version 450
// Fractal decoding, output: tile samples from the working image, base + round(value / 16),
// plus the residual layer's correction when uResidualBin > 0, written as heights in metres
// (sample * quantum) into one layer of a float height texture array. Border samples of a code
// with an exact border are base + their coded value (fractal::forEachBorderSample's loop order).
layout(local_size_x = 8, local_size_y = 8) in;

layout(binding = 1, r32ui) readonly uniform uimage2DArray uWorking;
layout(binding = 4, r32i) readonly uniform iimage2DArray uResidual;
layout(binding = 5, r32f) writeonly uniform image2DArray uHeights;
layout(binding = 6, r32i) readonly uniform iimage2DArray uBorder;
uniform int uLayer;        // decoder slot
uniform int uTargetLayer;  // layer of uHeights
uniform ivec2 uShape;      // tile samples
uniform int uBase;         // tile minimum, steps
uniform int uResidualBin;  // 2e + 1, or 0 for no residual
uniform float uQuantum;    // metres per step
uniform int uHasBorder;    // 1: the slot's code has an exact border

// The position of p on the clockwise border loop of fractal::forEachBorderSample, or -1 inside.
int borderIndex(ivec2 p) {
  int w = uShape.x - 1, h = uShape.y - 1;
  if (p.y == 0) return p.x;
  if (p.x == w) return w + p.y;
  if (p.y == h) return w + h + (w - p.x);
  if (p.x == 0) return 2 * w + h + (h - p.y);
  return -1;
}

void main() {
  ivec2 p = ivec2(gl_GlobalInvocationID.xy);
  if (p.x >= uShape.x || p.y >= uShape.y) return;
  uint value = imageLoad(uWorking, ivec3(p, uLayer)).x;
  // Integer arithmetic wraps modulo 2^32, as on the CPU.
  int sample_ = uBase + int((value + 8u) >> 4);
  if (uResidualBin > 0) sample_ += imageLoad(uResidual, ivec3(p, uLayer)).x * uResidualBin;
  int k = uHasBorder != 0 ? borderIndex(p) : -1;
  if (k >= 0) sample_ = uBase + imageLoad(uBorder, ivec3(k, 0, uLayer)).x;
  imageStore(uHeights, ivec3(p, uTargetLayer), vec4(float(sample_) * uQuantum));
}
