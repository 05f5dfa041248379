#version 450 core
// Geometry clipmaps (seed 004 section 2.3): one vertex of a level's footprint. gl_VertexID is
// the vertex's id in the level's n x n grid (y * n + x, local y running south); its height is
// fetched from the level's layer of the toroidal texture array and geomorphed towards the
// coarser level's surface in the transition band at the level's border.

uniform mat4 uClipFromRelative;  // camera-relative world -> clip
uniform int uN;                  // vertices a level side
uniform int uTextureSize;        // n + 1 texels a side
uniform int uLevel;
uniform int uHasCoarser;         // 0 for the coarsest level
uniform ivec2 uOrigin;           // the level's vertex (0, 0), level units (col, row)
uniform float uScale;            // full-resolution samples per level unit, 2^level
uniform vec2 uCameraSample;      // the camera, full-resolution (col, row)
uniform vec2 uViewerLocal;       // the viewer in level units, relative to the origin
uniform float uBlendStart;       // |local - viewer| (level units) where the blend starts
uniform float uBlendWidth;       // and its width: weight 1 one unit inside the border
uniform vec2 uSpacing;           // metres per full-resolution sample (x east, y south->north)
uniform float uExaggeration;
uniform float uCameraZ;          // metres
layout(binding = 0) uniform sampler2DArray uHeights;  // RG32F (z_f, z_c), one layer per level

out vec3 vRelativePosition;  // camera-relative world position, metres
out float vHeight;           // the drawn (geomorphed) height, metres
out vec3 vFineUV;            // this level's layer, for normals
out vec3 vCoarseUV;          // the coarser level's layer at the same point
out vec2 vSample;            // full-resolution (col, row), to clip to the terrain
out float vBlend;
flat out int vLevel;

// sampleAt mod uTextureSize in [0, uTextureSize) (GLSL's % is undefined for negative operands):
// a float floor division, then one step of correction for its rounding.
ivec2 toroidalTexel(ivec2 sampleAt) {
  ivec2 texel = sampleAt - uTextureSize * ivec2(floor(vec2(sampleAt) / float(uTextureSize)));
  texel += uTextureSize * ivec2(lessThan(texel, ivec2(0)));
  texel -= uTextureSize * ivec2(greaterThanEqual(texel, ivec2(uTextureSize)));
  return texel;
}

void main() {
  ivec2 local = ivec2(gl_VertexID % uN, gl_VertexID / uN);
  ivec2 sampleAt = uOrigin + local;
  ivec2 texel = toroidalTexel(sampleAt);
  vec2 heights = texelFetch(uHeights, ivec3(texel, uLevel), 0).rg;
  vec2 d = abs(vec2(local) - uViewerLocal);
  float blend = float(uHasCoarser) * clamp((max(d.x, d.y) - uBlendStart) / uBlendWidth, 0.0, 1.0);
  float height = mix(heights.x, heights.y, blend);
  // The vertex's full-resolution sample is an integer, exact in float: every level computes a
  // shared vertex's position with the same operations, so neighbouring levels meet exactly.
  vec2 fromCamera = vec2(sampleAt) * uScale - uCameraSample;
  vRelativePosition = vec3(fromCamera.x * uSpacing.x, -fromCamera.y * uSpacing.y,
                           height * uExaggeration - uCameraZ);
  vHeight = height;
  float size = float(uTextureSize);
  // Unwrapped coordinates: the sampler's REPEAT wrap is the toroidal addressing.
  vFineUV = vec3((vec2(sampleAt) + 0.5) / size, float(uLevel));
  vCoarseUV = vec3((vec2(sampleAt) * 0.5 + 0.5) / size, float(min(uLevel + uHasCoarser, uLevel + 1)));
  vSample = vec2(sampleAt) * uScale;
  vBlend = blend;
  vLevel = uLevel;
  gl_Position = uClipFromRelative * vec4(vRelativePosition, 1.0);
}
