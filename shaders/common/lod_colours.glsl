// Shading modes (RenderSettings::mode): 0 lit, 1 level of detail (the lit colour tinted by a
// palette entry per level, so that rings and LOD transitions can be seen), 2 screen-space error
// (the geometric error of the drawn data projected at the pixel's distance, green at 0 px,
// yellow at half of uSseRedPx, red at uSseRedPx and beyond: the colours of the bench's error
// images).
uniform int uShadingMode;
uniform float uPixelsPerRadian;  // viewport height / (2 tan(fovY / 2)): pixels per metre at 1 m
uniform float uSseRedPx;         // error drawn fully red, pixels

float luminance(vec3 colour) {
  return dot(colour, vec3(0.299, 0.587, 0.114));
}

vec3 levelOfDetailTint(vec3 litColour, int level) {
  const vec3 palette[8] = vec3[8](vec3(0.90, 0.20, 0.20), vec3(0.95, 0.60, 0.15),
                                  vec3(0.95, 0.90, 0.20), vec3(0.35, 0.80, 0.30),
                                  vec3(0.20, 0.75, 0.85), vec3(0.25, 0.40, 0.95),
                                  vec3(0.60, 0.30, 0.90), vec3(0.90, 0.35, 0.75));
  return clamp(palette[level % 8] * (0.35 + 0.9 * luminance(litColour)), 0.0, 1.0);
}

// errorM: vertical error of the drawn surface, metres (exaggeration applied); distanceM: from
// the camera. The error is taken as seen face-on, an upper bound of its projection.
vec3 screenSpaceErrorTint(vec3 litColour, float errorM, float distanceM) {
  float errorPx = errorM * uPixelsPerRadian / max(distanceM, 1e-3);
  float t = clamp(errorPx / max(uSseRedPx, 1e-6), 0.0, 1.0);
  vec3 colour = vec3(min(1.0, 2.0 * t), min(1.0, 2.0 * (1.0 - t)), 0.0);
  return clamp(colour * (0.35 + 0.9 * luminance(litColour)), 0.0, 1.0);
}

vec3 applyShadingMode(vec3 litColour, int level, float errorM, vec3 relativePosition) {
  if (uShadingMode == 1) return levelOfDetailTint(litColour, level);
  if (uShadingMode == 2) return screenSpaceErrorTint(litColour, errorM, length(relativePosition));
  return litColour;
}
