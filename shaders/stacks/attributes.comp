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
// Geomorph targets (lod/stacks/stitched_quadrangulation.hpp, MorphTarget), at the vertices'
// indices, written when uWriteMorph is set.
// Two vec4 a vertex: position and cell bits, normal and packed material weights.
layout(std430, binding = 10) writeonly buffer MorphTargets { vec4 morphTargets[]; };
uniform int uIsoTwice;  // twice the iso-value in smoothed units
uniform int uVertexCapacity;
uniform int uWriteMorph;
uniform int uSeamBandCells;  // the seam blend baked into stitched nodes' vertices (0: none)
#include "stacks/seam_weight.glsl"

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

// Cell c's corner densities and classification.
uint classifyCell(ivec3 c, out int corner[8]) {
  uint classification = 0u;
  for (int k = 0; k < 8; ++k) {
    corner[k] = densityAt(c + cornerOffset(k));
    if (2u * uint(corner[k]) > uint(uIsoTwice)) classification |= 1u << k;
  }
  return classification;
}

// The cell-local mean of the edge crossings of a cell with a vertex.
vec3 crossingMean(int corner[8], uint classification) {
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
  return vec3(px / count, py / count, pz / count);
}

// A cell-local position of level `level`'s volume whose cell (0, 0, 0) is sample `origin`, in
// world metres.
vec3 placeInWorld(vec3 p, ivec3 c, ivec3 origin, int level) {
  float spacing = uLevelGeometry[level].x, cellM = uLevelGeometry[level].y;
  float baseM = uLevelGeometry[level].z;
  precise float xM = (float(origin.x + c.x) + p.x) * spacing;
  precise float yM = (float(origin.y + c.y) + p.y) * spacing;
  precise float zM = baseM + (float(origin.z + c.z) + p.z + 0.5) * cellM;
  return vec3(xM, yM, zM);
}

// The geomorph target of a vertex at `own` in coarse cell `cc` (coarse-local), as the CPU
// reference's coarseMorphTarget: the coarse cell's vertex, else its nearest neighbour's.
vec3 coarseMorphTarget(ivec3 cc, ivec3 coarseOrigin, int coarseLevel, vec3 own) {
  bool wasCoarse = gCoarse;
  gCoarse = true;
  int corner[8];
  uint classification = classifyCell(cc, corner);
  vec3 best = own;
  if (cellHasVertex(classification)) {
    best = placeInWorld(crossingMean(corner, classification), cc, coarseOrigin, coarseLevel);
  } else {
    precise float bestDistance = 3.0e38;  // above any distance here
    for (int dz = -1; dz <= 1; ++dz) {
      for (int dy = -1; dy <= 1; ++dy) {
        for (int dx = -1; dx <= 1; ++dx) {
          ivec3 n = cc + ivec3(dx, dy, dz);
          classification = classifyCell(n, corner);
          if (!cellHasVertex(classification)) continue;
          vec3 p = placeInWorld(crossingMean(corner, classification), n, coarseOrigin, coarseLevel);
          precise float ex = p.x - own.x, ey = p.y - own.y, ez = p.z - own.z;
          precise float distance = ex * ex + ey * ey + ez * ez;
          if (distance < bestDistance) {
            bestDistance = distance;
            best = p;
          }
        }
      }
    }
  }
  gCoarse = wasCoarse;
  return best;
}

// MorphTarget's w (lod/stacks/seam_blend.hpp, packMorphTargetCell): the cell's border bits
// (bit 2a: first along axis a, 2a + 1: last) and the cell itself, 6 bits an axis from bit 6.
uint packedCell(ivec3 c, int n) {
  uint bits = 0u;
  for (int a = 0; a < 3; ++a) {
    if (c[a] == 0) bits |= 1u << (2 * a);
    if (c[a] == n - 1) bits |= 1u << (2 * a + 1);
    bits |= uint(c[a] & 63) << (6 + 6 * a);
  }
  return bits;
}

// The vertex of cell c of level `level`'s volume whose cell (0, 0, 0) is sample `origin` (the
// coarser volume while gCoarse is set): position, normal, material weights (the CPU
// reference's cellVertex).
StackVertex cellVertex(ivec3 c, ivec3 origin, int level) {
  float spacing = uLevelGeometry[level].x, cellM = uLevelGeometry[level].y;
  int corner[8];
  uint classification = classifyCell(c, corner);
  vec3 mean = crossingMean(corner, classification);
  precise float px = mean.x, py = mean.y, pz = mean.z;
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
  v.position = vec4(placeInWorld(mean, c, origin, level), float(level));  // w: its level
  v.normal = len > 0.0 ? vec4(-gx / len, -gy / len, -gz / len, 0.0) : vec4(0.0, 0.0, 1.0, 0.0);
  v.materials = vec4(channel.x / sum, channel.y / sum, channel.z / sum, channel.w / sum);
  return v;
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
  ivec3 fineCell = c, fineOrigin = origin;
  int fineLevel = level;
  if (gCoarse) {
    c /= 2;
    origin /= 2;
    level += 1;
  }
  StackVertex v = cellVertex(c, origin, level);
  bool blends = uSeamBandCells > 0 && nodes[node].stitch.w != 0;
  if (uWriteMorph == 0 && !blends) {
    vertices[at] = v;
    return;
  }
  // The target (MorphTarget): the vertex itself unless it can slide; the coarse cell's whole
  // vertex where that cell has one, else the nearest neighbour's position with its own shading.
  StackVertex target = v;
  bool hasCoarser = fineLevel + 1 < 16 && uLevelLayout[fineLevel + 1].z > 0;
  if (hasCoarser && !gCoarse) {
    ivec3 cc = fineCell / 2, coarseOrigin = fineOrigin / 2;
    gCoarse = true;
    int corner[8];
    bool coarseHasVertex = cellHasVertex(classifyCell(cc, corner));
    if (coarseHasVertex) target = cellVertex(cc, coarseOrigin, fineLevel + 1);
    gCoarse = false;
    if (!coarseHasVertex) target.position.xyz = coarseMorphTarget(cc, coarseOrigin, fineLevel + 1, v.position.xyz);
  }
  // The seam blend (lod/stacks/seam_blend.hpp, seamBlendedVertex): towards the coarser surface
  // next to a coarser neighbour.
  float weight = blends ? seamBlendWeight(fineCell, uint(nodes[node].stitch.w), nodes[node].stitch.xyz, n - 1,
                                          uSeamBandCells)
                        : 0.0;
  if (weight > 0.0) {
    precise vec3 p = target.position.xyz * weight + v.position.xyz * (1.0 - weight);
    precise vec3 nn = target.normal.xyz * weight + v.normal.xyz * (1.0 - weight);
    precise float len = sqrt(nn.x * nn.x + nn.y * nn.y + nn.z * nn.z);
    v.position.xyz = p;
    if (len > 0.0) v.normal.xyz = nn / len;
    v.materials = target.materials * weight + v.materials * (1.0 - weight);
  }
  vertices[at] = v;
  if (uWriteMorph == 0) return;
  morphTargets[2 * at] = vec4(target.position.xyz, float(packedCell(fineCell, n)));
  morphTargets[2 * at + 1] = vec4(target.normal.xyz, uintBitsToFloat(packUnorm4x8(target.materials)));
}
