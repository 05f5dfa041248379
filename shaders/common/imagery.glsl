// Imagery draped on the terrain: a virtual texture over up to kImageryMaxLayers imagery
// pyramids (later layers over earlier ones). GL side: src/tellus/render/imagery/imagery_textures.cpp;
// CPU twin of the lookup: src/tellus/lod/imagery/imagery_placement.cpp:imageryResolve() (same
// names, same maths; keep the two in step).
//
// Pages are the pyramids' tiles, numbered layer by layer, level by level (0 = full resolution),
// row by row (lod/imagery/imagery_pages.hpp). The page table holds, per page, the slot of the
// page a lookup reads (its own when resident, else its nearest resident ancestor's) and that
// page's level; a slot is a layer of uImageryPages, the page's texels with a border of
// uImageryBorder texels from its neighbours so that bilinear filtering crosses page edges.
// Every lookup writes the frame's stamp into the feedback at the page it wanted; the CPU reads
// the feedback a frame or more late and pages in what was wanted.
const int kImageryMaxLayers = 4;
const int kImageryMaxLevels = 16;
const int kImageryDensityBins = 128;  // quarter-octaves of screen pixels a texel covers, 2^-16 to 2^16

uniform int uImageryLayerCount;          // 0: no imagery
uniform int uImageryFrame;               // the stamp lookups write into the feedback (> 0)
uniform int uImageryTileSize;            // texels a page side, border excluded
uniform int uImageryBorder;              // border texels on each side of a slot
uniform int uImageryHistogramOffset;     // where the texel-density histogram starts in the feedback
// Per layer: the level-0 texel under the camera, and texels per frame unit (the placement's
// scale: texel = camera texel + scale * camera-relative position).
uniform vec2 uImageryCameraTexel[kImageryMaxLayers];
uniform vec2 uImageryTexelsPerUnit[kImageryMaxLayers];
uniform int uImageryLevels[kImageryMaxLayers];
// > 0: the layer repeats every this many level-0 texels east-west (round the globe).
uniform float uImageryWrapTexels[kImageryMaxLayers];
// Per layer and level (layer * kImageryMaxLevels + level): first page, tiles across, tiles down.
// Globe frames: the camera's longitude and latitude, degrees (imageryRelativeLonLat).
uniform vec2 uImageryCameraLonLat;
uniform ivec4 uImageryLevelPages[kImageryMaxLayers * kImageryMaxLevels];
layout(binding = 14) uniform sampler2DArray uImageryPages;
layout(std430, binding = 14) readonly buffer ImageryPageTable { uint imageryPageTable[]; };
layout(std430, binding = 15) buffer ImageryFeedback { uint imageryFeedback[]; };

// The page of `level` holding level-0 texel `texel`, -1 outside the layer.
int imageryPageIndex(int layer, vec2 texel, int level) {
  ivec4 pages = uImageryLevelPages[layer * kImageryMaxLevels + level];
  ivec2 page = ivec2(floor(texel / (float(uImageryTileSize) * exp2(float(level)))));
  if (page.x < 0 || page.y < 0 || page.x >= pages.y || page.y >= pages.z) return -1;
  return pages.x + page.y * pages.y + page.x;
}

// The premultiplied sRGB colour of `layer` at level-0 texel `texel` read at `level` (or the
// nearest resident ancestor's level, returned in `resolvedLevel`); 0 outside the layer.
vec4 imageryAtLevel(int layer, vec2 texel, int level, out int resolvedLevel) {
  resolvedLevel = level;
  int page = imageryPageIndex(layer, texel, level);
  if (page < 0) return vec4(0.0);
  uint entry = imageryPageTable[page];
  if (entry == 0u) return vec4(0.0);
  int slot = int(entry & 0xFFFFu) - 1;
  resolvedLevel = int((entry >> 16) & 0xFFu);
  float tile = float(uImageryTileSize);
  vec2 atResolved = texel / exp2(float(resolvedLevel));
  vec2 local = atResolved - floor(atResolved / tile) * tile;
  vec2 uv = (local + float(uImageryBorder)) / (tile + 2.0 * float(uImageryBorder));
  return textureLod(uImageryPages, vec3(uv, float(slot)), 0.0);
}

// All layers composited at camera-relative frame position `relative` (flat renderers: world
// metres east and north of the camera): premultiplied sRGB, alpha where imagery covers.
// Trilinear: the two levels around the pixel's footprint, blended. Writes the feedback.
vec4 imageryColour(vec2 relative) {
  vec4 colour = vec4(0.0);
  int drawnLevel = -1;
  float footprint = 0.0;  // level-0 texels^2 a pixel covers, of the layer drawn on top
  for (int layer = 0; layer < uImageryLayerCount; ++layer) {
    vec2 texel = uImageryCameraTexel[layer] + uImageryTexelsPerUnit[layer] * relative;
    vec2 dx = dFdx(texel), dy = dFdy(texel);  // before the wrap: continuous across the antimeridian
    float wrap = uImageryWrapTexels[layer];
    if (wrap > 0.0) texel.x -= wrap * floor(texel.x / wrap);
    float lambda = 0.5 * log2(max(max(dot(dx, dx), dot(dy, dy)), 1e-12));
    int levels = uImageryLevels[layer];
    float clamped = clamp(lambda, 0.0, float(levels - 1));
    int fine = int(floor(clamped));
    int coarse = min(fine + 1, levels - 1);
    int fineResolved, coarseResolved;
    vec4 a = imageryAtLevel(layer, texel, fine, fineResolved);
    vec4 b = imageryAtLevel(layer, texel, coarse, coarseResolved);
    int wanted = imageryPageIndex(layer, texel, fine);
    if (wanted >= 0) imageryFeedback[wanted] = uint(uImageryFrame);
    vec4 layerColour = mix(a, b, clamped - float(fine));
    if (layerColour.a > 0.5) {
      drawnLevel = fineResolved;
      footprint = abs(dx.x * dy.y - dx.y * dy.x);
    }
    colour = layerColour + colour * (1.0 - layerColour.a);
  }
  // Texel density where imagery is drawn, one pixel in 16: screen pixels a texel of the level
  // read covers.
  ivec2 pixel = ivec2(gl_FragCoord.xy);
  if (drawnLevel >= 0 && (pixel.x & 3) == 0 && (pixel.y & 3) == 0 && footprint > 0.0) {
    float pixelsPerTexel = exp2(2.0 * float(drawnLevel)) / footprint;
    int bin = clamp(int(floor(4.0 * log2(pixelsPerTexel))) + kImageryDensityBins / 2, 0,
                    kImageryDensityBins - 1);
    atomicAdd(imageryFeedback[uImageryHistogramOffset + bin], 1u);
  }
  return colour;
}

// Globe renderers: the frame position of ECEF point `ecef` relative to the camera, degrees of
// longitude (wrapped to -180..180) and latitude. The latitude is the ellipsoid surface's
// (exact at height 0; metres off on mountains, less than a Landsat texel).
vec2 imageryRelativeLonLat(vec3 ecef) {
  const float kE2 = 0.00669437999014;  // WGS84 first eccentricity squared
  float lon = degrees(atan(ecef.y, ecef.x));
  float lat = degrees(atan(ecef.z, (1.0 - kE2) * length(ecef.xy)));
  vec2 relative = vec2(lon, lat) - uImageryCameraLonLat;
  relative.x -= 360.0 * floor((relative.x + 180.0) / 360.0);
  return relative;
}

vec3 imagerySrgbToLinear(vec3 c) {
  return mix(c / 12.92, pow((c + 0.055) / 1.055, vec3(2.4)), step(vec3(0.04045), c));
}

// `albedo` (linear) with the imagery `colour` (imageryColour) over it.
vec3 drapeImagery(vec3 albedo, vec4 colour) {
  if (colour.a <= 0.0) return albedo;
  return mix(albedo, imagerySrgbToLinear(colour.rgb / colour.a), colour.a);
}
