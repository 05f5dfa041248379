// Where a stack terrain meets the sky (render/stacks/stack_sky_texture.hpp): per column the top
// of its highest layer, bilinear between column centres, the highest of `span` x `span` columns
// on large terrains. Imagery is an orthophoto of those tops: it is draped only there.
layout(binding = 13) uniform sampler2D uStackSkyHeights;  // R16: top / uStackSkyScaleM
uniform float uStackSkyWorldToTexel;  // texels a world metre
uniform float uStackSkyTexelOffset;   // texel coordinate of world 0
uniform float uStackSkyScaleM;        // metres of a texel value 1.0
uniform float uStackSkySpanM;         // world metres a texel spans

// How much of an orthophoto belongs at world point `worldM` (metres, unexaggerated) with unit
// normal `normal` (of the unexaggerated surface): 1 on the tops facing the sky, 0 on cave
// floors and under overhangs (more than a few metres below the top of their column) and on
// walls. `toleranceM`: how far below the top the drawn surface may lie (a coarse level's error).
float stackSkyExposure(vec3 worldM, vec3 normal, float toleranceM) {
  vec2 texel = worldM.xy * uStackSkyWorldToTexel + uStackSkyTexelOffset;
  float topM = texture(uStackSkyHeights, texel / vec2(textureSize(uStackSkyHeights, 0))).r * uStackSkyScaleM;
  // A slope of 1 drops a span between column centres: the bilinear top may stand that far
  // above a surface that is the top.
  float below = topM - worldM.z;
  float margin = toleranceM + uStackSkySpanM;
  float atTop = 1.0 - smoothstep(margin, 2.0 * margin, below);
  float facingUp = smoothstep(0.2, 0.45, normal.z);
  return atTop * facingUp;
}
