#version 450 core
// Imagery draped on the spiral globe: the node's texture as it is, unlit (the seed's decals are
// "not disturbing the data"), premultiplied alpha (0 beyond the image and under its mask).
// Stored as the source has it (sRGB, as the frame is written: no decoding).
// uLevelTint > 0 mixes in a colour per texel density (the seed's Figures 9 and 15).
uniform sampler2D uImage;
uniform vec3 uTint;
uniform float uLevelTint;

in vec2 vTexel;
out vec4 fragColour;

void main() {
  vec4 texel = texture(uImage, vTexel);
  if (texel.a < 1.0 / 255.0) discard;
  fragColour = vec4(mix(texel.rgb, uTint * texel.a, uLevelTint), texel.a);
}
