// The spiral globe's heights (seed 001): the stack of height windows round the focal point
// (src/tellus/lod/spiral/spiral_height_levels.hpp, whose spiralWindowHeight, spiralLevelDepthFor,
// spiralCoarserShare and spiralLookupHeight this file mirrors), shared by the spiral
// (spiral.vert) and what is draped on it (imagery.vert) so both find the same surface. Needs
// uStepsPerRevolution.

const int kMaxLevels = 24;

uniform float uStepsPerRevolution;  // the spiral's vertices a revolution
uniform bool uBlendDepths;          // mix each vertex's two depths (spiralCoarserShare)

// Heights: RG = (metres above the ellipsoid, the geoid's undulation there).
uniform sampler2D uBaseHeights;       // the whole Earth at uBaseDepth, columns wrap
uniform vec2 uBaseFocal;              // the focal point in the base's samples (x east, y south)
uniform float uBaseStepRad;
uniform sampler2DArray uLevelHeights; // one window a depth uBaseDepth + 1 + i
uniform int uLevelCount;
uniform int uLevelLayer[kMaxLevels];  // the window's layer; -1: none yet
uniform vec2 uLevelFocal[kMaxLevels];
uniform float uLevelStepRad[kMaxLevels];
uniform int uBaseDepth;
uniform int uTileCells;

// The depth whose sample spacing equals `spacingRad`, fractional.
float spiralWantedDepth(float spacingRad) {
  return log2(3.14159265 / (float(uTileCells) * spacingRad));
}

int spiralLevelDepthFor(float spacingRad) {
  if (!(spacingRad > 0.0)) return uBaseDepth + uLevelCount;
  float wanted = ceil(spiralWantedDepth(spacingRad));
  return int(clamp(wanted, float(uBaseDepth), float(uBaseDepth + uLevelCount)));
}

// The next coarser depth's share of a blended vertex's height (spiralCoarserShare), for the
// depth spiralLevelDepthFor gave it.
float spiralCoarserShare(float spacingRad, int depth) {
  if (!uBlendDepths || !(spacingRad > 0.0) || depth <= uBaseDepth) return 0.0;
  return clamp(float(depth) - spiralWantedDepth(spacingRad), 0.0, 1.0);
}

vec2 texelAt(int layer, ivec2 at, ivec2 size) {
  at = clamp(at, ivec2(0), size - 1);
  return layer < 0 ? texelFetch(uBaseHeights, at, 0).rg
                   : texelFetch(uLevelHeights, ivec3(at, layer), 0).rg;
}

// The surface at (x, y) in the layer's samples (spiralWindowHeight).
vec2 windowHeight(int layer, vec2 xy) {
  ivec2 size = layer < 0 ? textureSize(uBaseHeights, 0) : textureSize(uLevelHeights, 0).xy;
  if (layer < 0) {
    float around = float(size.x - 1);
    xy.x -= around * floor(xy.x / around);
  }
  xy = clamp(xy, vec2(0.0), vec2(size - 1));
  ivec2 at = min(ivec2(xy), size - 2);
  vec2 f = xy - vec2(at);
  // The cell's two triangles, split from its north-east to its south-west sample (the
  // reference mesh's diagonal), as spiralWindowHeight.
  vec2 ne = texelAt(layer, at + ivec2(1, 0), size), sw = texelAt(layer, at + ivec2(0, 1), size);
  if (f.x + f.y <= 1.0) {
    vec2 nw = texelAt(layer, at, size);
    return nw + (ne - nw) * f.x + (sw - nw) * f.y;
  }
  vec2 se = texelAt(layer, at + ivec2(1, 1), size);
  return se + (sw - se) * (1.0 - f.x) + (ne - se) * (1.0 - f.y);
}

// Where a vertex (dlat, dlon) from the focal point finds its heights starting at `fromDepth`:
// that depth's window if it holds the vertex, or the deepest coarser one's, or the base.
// Returns (layer, x, y, step radians); layer -1 is the base.
struct SpiralHeightAt {
  int layer;
  vec2 xy;
  float stepRad;
};
SpiralHeightAt spiralHeightFrom(vec2 latLon, int fromDepth) {
  int layer = -1;
  vec2 xy = uBaseFocal + vec2(latLon.y, -latLon.x) / uBaseStepRad;
  float stepRad = uBaseStepRad;
  for (int depth = fromDepth; depth > uBaseDepth; --depth) {
    int i = depth - uBaseDepth - 1;
    if (uLevelLayer[i] < 0) continue;
    vec2 at = uLevelFocal[i] + vec2(latLon.y, -latLon.x) / uLevelStepRad[i];
    ivec2 size = textureSize(uLevelHeights, 0).xy;
    if (all(greaterThanEqual(at, vec2(1.0))) && all(lessThanEqual(at, vec2(size - 2)))) {
      layer = uLevelLayer[i];
      xy = at;
      stepRad = uLevelStepRad[i];
      break;
    }
  }
  return SpiralHeightAt(layer, xy, stepRad);
}

// The two places a vertex at `radius` (spacing radius 2 pi / n) takes its heights from: the
// depth that resolves its spacing (or the deepest coarser window holding it) and, blended, the
// same a depth coarser, with that one's share (0: unblended).
struct SpiralBlend {
  SpiralHeightAt finer;
  SpiralHeightAt coarser;
  float share;
};
SpiralBlend spiralBlendAt(vec2 latLon, float radius) {
  float spacing = radius * 6.2831853 / uStepsPerRevolution;
  int depth = spiralLevelDepthFor(spacing);
  SpiralBlend blend;
  blend.finer = spiralHeightFrom(latLon, depth);
  blend.share = spiralCoarserShare(spacing, depth);
  blend.coarser = blend.share > 0.0 ? spiralHeightFrom(latLon, depth - 1) : blend.finer;
  return blend;
}

// The blended surface: (height above the ellipsoid, undulation).
vec2 spiralBlendedHeight(SpiralBlend blend) {
  vec2 finer = windowHeight(blend.finer.layer, blend.finer.xy);
  if (!(blend.share > 0.0)) return finer;
  vec2 coarser = windowHeight(blend.coarser.layer, blend.coarser.xy);
  return finer + (coarser - finer) * blend.share;
}
