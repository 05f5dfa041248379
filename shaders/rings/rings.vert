#version 450 core
// Rings renderer (seed 000): displaces a static flat patch mesh with heights from the GPU tile
// cache (a texture array, one tile per layer, found through a page table) and stitches the
// patch's edges to coarser neighbours. One instance per patch; one draw per level of detail.
//
// Units: grid positions are integer level-0 sample coordinates (col east, row south); world
// positions leave the shader camera-relative (x east, y north, z up, metres), built from
// integer differences to the camera's sample so that shared vertices of neighbouring patches
// are bit-identical and nothing jitters far from the origin.

const int kMaxLevels = 24;

layout(location = 0) in uvec4 aVertex;  // PatchVertex: x, z, edge bits, odd flag
// Per instance: patch x, patch y, lod | orientation << 4 | coarserOutside << 8,
// data level | up << 5 | right << 10 | down << 15 | left << 20 (levels of the edges).
layout(location = 1) in ivec4 aPatch;

uniform mat4 uViewProjection;        // camera-relative world -> clip
uniform ivec2 uCameraSample;         // camera position in level-0 samples (col, row), floored
uniform vec2 uCameraFraction;        // the rest of it, metres (east, south)
uniform float uCameraHeight;         // camera z, metres
uniform vec2 uSampleSpacing;         // level-0 metres between samples (east-west, north-south)
uniform float uExaggeration;         // vertical scale
uniform ivec2 uDataSize;             // level-0 data width and height, samples
uniform int uTileSize;               // cells per tile side (a patch is one level-0 tile)
uniform int uMeshStride;             // level-0 samples per mesh cell at this draw's LOD
uniform int uOutwardEdges[9];        // the seed's look-up: orientation -> outward edge bits
uniform int uLevelOffset[kMaxLevels];  // page table: first entry of each level
uniform int uLevelTilesX[kMaxLevels];  // page table: tiles per row of each level

layout(std430, binding = 0) readonly buffer PageTable { int slotOfTile[]; };
layout(binding = 0) uniform sampler2DArray uHeights;  // R32F metres, (tileSize + 1)^2 per layer

out float vHeight;
out vec3 vRelativePosition;
out vec2 vSample;        // position in samples of the patch's data tile (for normals)
flat out int vSlot;      // layer of the patch's data tile
flat out int vLevel;     // pyramid level of the patch's data
flat out int vLod;       // the patch's level of detail

int tileSlot(ivec2 tile, int level) {
  return slotOfTile[uLevelOffset[level] + tile.y * uLevelTilesX[level] + tile.x];
}

// Height at level-0 sample g from pyramid level `level`, read from the tile of that level that
// holds `patchXY`. Exact samples are fetched, in-between points interpolated bilinearly from the
// level's samples; the same g and level give bit-identical results in neighbouring tiles
// (border samples are shared and an exact sample never blends).
float heightAt(ivec2 g, int level, ivec2 patchXY) {
  ivec2 tile = patchXY >> level;
  int slot = tileSlot(tile, level);
  ivec2 rel = g - tile * (uTileSize << level);
  ivec2 i0 = rel >> level;
  ivec2 rem = rel - (i0 << level);
  float h00 = texelFetch(uHeights, ivec3(i0, slot), 0).r;
  if (rem == ivec2(0)) return h00;
  float h10 = rem.x != 0 ? texelFetch(uHeights, ivec3(i0 + ivec2(1, 0), slot), 0).r : h00;
  float h01 = rem.y != 0 ? texelFetch(uHeights, ivec3(i0 + ivec2(0, 1), slot), 0).r : h00;
  float h11 = (rem.x != 0 && rem.y != 0) ? texelFetch(uHeights, ivec3(i0 + 1, slot), 0).r
                                         : (rem.x != 0 ? h10 : h01);
  vec2 f = vec2(rem) / float(1 << level);
  return mix(mix(h00, h10, f.x), mix(h01, h11, f.x), f.y);
}

void main() {
  ivec2 patchXY = aPatch.xy;
  int lod = aPatch.z & 15;
  int orientation = (aPatch.z >> 4) & 15;
  bool coarserOutside = ((aPatch.z >> 8) & 1) != 0;
  int dataLevel = aPatch.w & 31;
  int edges = int(aVertex.z);

  // Stitching: on edges facing a coarser ring, odd vertices move onto the previous even one.
  int stitch = coarserOutside ? uOutwardEdges[orientation] : 0;
  ivec2 grid = ivec2(aVertex.xy);
  if (aVertex.w != 0u && (edges & stitch) != 0) {
    if ((edges & 5) != 0) grid.x -= 1;  // up or down edge: previous vertex to the west
    else grid.y -= 1;                   // left or right edge: previous vertex to the north
  }
  // Edge vertices take their height from the coarser data level of the two patches that share
  // the edge (corners: of all their edges).
  int level = dataLevel;
  for (int e = 0; e < 4; ++e) {
    if ((edges & (1 << e)) != 0) level = max(level, (aPatch.w >> (5 + 5 * e)) & 31);
  }
  ivec2 g = min(patchXY * uTileSize + grid * uMeshStride, uDataSize - 1);
  float height = heightAt(g, level, patchXY);

  vec2 eastSouth = vec2(g - uCameraSample) * uSampleSpacing - uCameraFraction;
  vec3 position = vec3(eastSouth.x, -eastSouth.y, height * uExaggeration - uCameraHeight);

  ivec2 tile = patchXY >> dataLevel;
  vSample = vec2(g - tile * (uTileSize << dataLevel)) / float(1 << dataLevel);
  vSlot = tileSlot(tile, dataLevel);
  vLevel = dataLevel;
  vLod = lod;
  vHeight = height;
  vRelativePosition = position;
  gl_Position = uViewProjection * vec4(position, 1.0);
}
