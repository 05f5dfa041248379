// Normals of a heightfield stored in a texture (R32F, metres), computed per pixel from
// central differences of bilinearly filtered samples. Rows run north to south.
//   uv:        texture coordinate of the point
//   texel:     1 / texture size
//   spacingM:  ground distance between samples (x: east-west, y: north-south), metres
//   scale:     vertical exaggeration
vec3 heightfieldNormal(sampler2D heights, vec2 uv, vec2 texel, vec2 spacingM, float scale) {
  float west = texture(heights, uv - vec2(texel.x, 0.0)).r;
  float east = texture(heights, uv + vec2(texel.x, 0.0)).r;
  float north = texture(heights, uv - vec2(0.0, texel.y)).r;
  float south = texture(heights, uv + vec2(0.0, texel.y)).r;
  float dzdx = scale * (east - west) / (2.0 * spacingM.x);
  float dzdy = scale * (north - south) / (2.0 * spacingM.y);
  return normalize(vec3(-dzdx, -dzdy, 1.0));
}
