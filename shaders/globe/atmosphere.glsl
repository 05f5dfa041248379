// The globe renderers' aerial perspective (globe.frag and the streaming globes' own), under
// sky.frag's atmosphere.
uniform vec3 uEyeEcef;  // float: enough for the haze

// Aerial perspective under the atmosphere of sky.frag: the fraction of the view lost to haze
// over the part of the ray from the eye to this point that lies in the 60 km shell (all of it
// near the ground; from orbit only the last stretch, long at the limb).
float atmosphericHaze(vec3 relativePosition, vec3 eyeEcef) {
  const float kTop = 6431000.0;
  const float kVisibilityM = 500000.0;
  vec3 d = normalize(relativePosition);
  float distanceToPoint = length(relativePosition);
  float b = dot(eyeEcef, d);
  float c = dot(eyeEcef, eyeEcef) - kTop * kTop;
  float disc = max(b * b - c, 0.0);
  float enter = max(-b - sqrt(disc), 0.0);  // 0 when the eye is inside the shell
  float path = max(distanceToPoint - enter, 0.0);
  return 1.0 - exp(-path / kVisibilityM);
}

