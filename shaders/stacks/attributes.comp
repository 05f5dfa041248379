#version 450
// Stage 5, attributes of every vertex cell: position = mean of the edge crossings, normal = the
// 3D Sobel gradient at the 8 corners interpolated at the vertex, normalised material weights;
// written at the cell's vertex index. The arithmetic is the CPU reference's, step for step
// (precise: no fused multiply-adds). A stitched node's coarse cells with a vertex (their even
// cells) compute the coarser level's vertex of the coarse cell, from the coarser volume, as the
// coarser node computes it.
layout(local_size_x = 64) in;
#include "stacks/quad_common.glsl"
layout(std430, binding = 4) readonly buffer Smoothed { uvec4 smoothed[]; };
layout(std430, binding = 5) readonly buffer Cells { uvec4 cells[]; };
layout(std430, binding = 7) writeonly buffer Vertices { StackVertex vertices[]; };
layout(std430, binding = 9) readonly buffer CoarseSmoothed { uvec4 coarseSmoothed[]; };
uniform int uIsoTwice;  // twice the iso-value in smoothed units
uniform int uVertexCapacity;

int gNode = 0;
bool gCoarse = false;  // read the node's coarser volume
uvec4 sampleAt(ivec3 p) {  // volume-local sample, from -1
  ivec3 s = p + 1;
  if (gCoarse) {
    int cs = uCoarseSmoothSide;
    return coarseSmoothed[gNode * coarseBlock() + s.x + cs * (s.y + cs * s.z)];
  }
  return smoothed[gNode * rawBlock() + s.x + uSmoothSide * (s.y + uSmoothSide * s.z)];
}
int densityAt(ivec3 p) {
  uvec4 d = sampleAt(p);
  return int(d.x + d.y + d.z + d.w);
}

void main() {
  int node = int(gl_GlobalInvocationID.y);
  int linear = int(gl_GlobalInvocationID.x);
  int n = uNodeCells;
  if (node >= uBatchCount || linear >= cellBlock()) return;
  uvec4 cell = cells[node * cellBlock() + linear];
  uint at = nodes[node].dest.x + cell.y;
  if (!codeHasVertex(cell.x) || at >= uint(uVertexCapacity)) return;
  gNode = node;
  ivec3 c = ivec3(linear % n, (linear / n) % n, linear / (n * n));
  ivec3 origin = nodes[node].origin.xyz;
  int level = nodes[node].origin.w;
  gCoarse = nodes[node].stitch.w != 0 && coarseCell(node, c);
  if (gCoarse) {
    c /= 2;
    origin /= 2;
    level += 1;
  }
  float spacing = uLevelGeometry[level].x, cellM = uLevelGeometry[level].y;
  float baseM = uLevelGeometry[level].z;
  int corner[8];
  uint classification = 0u;
  for (int k = 0; k < 8; ++k) {
    corner[k] = densityAt(c + cornerOffset(k));
    if (2u * uint(corner[k]) > uint(uIsoTwice)) classification |= 1u << k;
  }
  precise float iso = float(uIsoTwice / 2);
  precise float px = 0.0, py = 0.0, pz = 0.0;
  int crossings = 0;
  for (int e = 0; e < 12; ++e) {
    int a = kCellEdges[e].x, b = kCellEdges[e].y;
    if (cornerInside(classification, a) == cornerInside(classification, b)) continue;
    precise float da = float(corner[a]), db = float(corner[b]);
    precise float t = (iso - da) / (db - da);
    vec3 pa = vec3(cornerOffset(a)), pb = vec3(cornerOffset(b));
    px += pa.x + t * (pb.x - pa.x);
    py += pa.y + t * (pb.y - pa.y);
    pz += pa.z + t * (pb.z - pa.z);
    ++crossings;
  }
  precise float count = float(crossings);
  px = px / count;
  py = py / count;
  pz = pz / count;
  precise float gx = 0.0, gy = 0.0, gz = 0.0;
  for (int k = 0; k < 8; ++k) {
    ivec3 p = c + cornerOffset(k);
    int sx = 0, sy = 0, sz = 0;
    for (int e = -1; e <= 1; ++e) {
      for (int f = -1; f <= 1; ++f) {
        int w = (2 - abs(e)) * (2 - abs(f));
        sx += w * (densityAt(p + ivec3(1, e, f)) - densityAt(p + ivec3(-1, e, f)));
        sy += w * (densityAt(p + ivec3(e, 1, f)) - densityAt(p + ivec3(e, -1, f)));
        sz += w * (densityAt(p + ivec3(e, f, 1)) - densityAt(p + ivec3(e, f, -1)));
      }
    }
    precise float wx = (k & 1) != 0 ? px : 1.0 - px;
    precise float wy = ((k >> 1) & 1) != 0 ? py : 1.0 - py;
    precise float wz = ((k >> 2) & 1) != 0 ? pz : 1.0 - pz;
    precise float weight = wx * wy * wz;
    gx += weight * float(sx);
    gy += weight * float(sy);
    gz += weight * float(sz);
  }
  gx = gx / spacing;
  gy = gy / spacing;
  gz = gz / cellM;
  precise float len = sqrt(gx * gx + gy * gy + gz * gz);
  // Materials: channel densities weighted by the air each corner holds, normalised (the CPU
  // reference's comment says why); the plain sums where every corner is full or empty.
  precise vec4 channel = vec4(0.0);
  uvec4 plain = uvec4(0u);
  for (int k = 0; k < 8; ++k) {
    uvec4 s = sampleAt(c + cornerOffset(k));
    precise float air = float(uint(uIsoTwice) - (s.x + s.y + s.z + s.w));
    channel.x += float(s.x) * air;
    channel.y += float(s.y) * air;
    channel.z += float(s.z) * air;
    channel.w += float(s.w) * air;
    plain += s;
  }
  precise float sum = channel.x + channel.y + channel.z + channel.w;
  if (!(sum > 0.0)) {
    channel = vec4(plain);
    sum = channel.x + channel.y + channel.z + channel.w;
  }
  StackVertex v;
  precise float xM = (float(origin.x + c.x) + px) * spacing;
  precise float yM = (float(origin.y + c.y) + py) * spacing;
  precise float zM = baseM + (float(origin.z + c.z) + pz + 0.5) * cellM;
  v.position = vec4(xM, yM, zM, float(level));  // w: the level that made the vertex
  v.normal = len > 0.0 ? vec4(-gx / len, -gy / len, -gz / len, 0.0) : vec4(0.0, 0.0, 1.0, 0.0);
  v.materials = vec4(channel.x / sum, channel.y / sum, channel.z / sum, channel.w / sum);
  vertices[at] = v;
}
