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

// The same for one layer of a texture array: uvw.xy in [0, 1] inside the layer, uvw.z the layer.
vec3 heightfieldNormalArray(sampler2DArray heights, vec3 uvw, vec2 texel, vec2 spacingM,
                            float scale) {
  float west = texture(heights, uvw - vec3(texel.x, 0.0, 0.0)).r;
  float east = texture(heights, uvw + vec3(texel.x, 0.0, 0.0)).r;
  float north = texture(heights, uvw - vec3(0.0, texel.y, 0.0)).r;
  float south = texture(heights, uvw + vec3(0.0, texel.y, 0.0)).r;
  float dzdx = scale * (east - west) / (2.0 * spacingM.x);
  float dzdy = scale * (north - south) / (2.0 * spacingM.y);
  return normalize(vec3(-dzdx, -dzdy, 1.0));
}
