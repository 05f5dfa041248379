// Level-of-detail colouring (ShadingMode::LevelOfDetail): the lit colour tinted by a palette
// entry per level, so that rings and LOD transitions can be seen. uShadingMode: 0 lit, 1 LOD.
uniform int uShadingMode;

vec3 levelOfDetailTint(vec3 litColour, int level) {
  const vec3 palette[8] = vec3[8](vec3(0.90, 0.20, 0.20), vec3(0.95, 0.60, 0.15),
                                  vec3(0.95, 0.90, 0.20), vec3(0.35, 0.80, 0.30),
                                  vec3(0.20, 0.75, 0.85), vec3(0.25, 0.40, 0.95),
                                  vec3(0.60, 0.30, 0.90), vec3(0.90, 0.35, 0.75));
  float light = dot(litColour, vec3(0.299, 0.587, 0.114));
  return clamp(palette[level % 8] * (0.35 + 0.9 * light), 0.0, 1.0);
}

vec3 applyShadingMode(vec3 litColour, int level) {
  return uShadingMode == 1 ? levelOfDetailTint(litColour, level) : litColour;
}
