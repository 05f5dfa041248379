#version 450 core
// The sky behind the globe: black space, and the atmosphere as a shell 60 km thick around the
// sphere through the ellipsoid point under the eye (so that the sky's ground meets the drawn
// ground at the horizon at any latitude), coloured by how much of it each view ray crosses (a thin
// blue rim seen from orbit, blue overhead and pale at the horizon from the ground), dimmed on
// the night side. Not a scattering model: a backdrop that reads as the sky.
uniform mat4 uInverseViewProjection;  // clip -> eye-relative ECEF
uniform vec3 uEye;                    // ECEF, metres (float: the sky needs no more)
uniform vec3 uSunEcef;                // unit, towards the sun
uniform float uGroundRadius;          // metres from the Earth's centre to the ellipsoid under the eye

in vec2 vNdc;
out vec4 fragColour;

const float kAtmosphereThickness = 60000.0;
// The longest path through the shell that starts on the ground: to the horizon and out.
const float kHorizontalPath = 876000.0;

// Distances along the ray (origin o, unit direction d) to the sphere of radius r: (near, far),
// or (-1, -1) when it misses.
vec2 sphere(vec3 o, vec3 d, float r) {
  float b = dot(o, d);
  float c = dot(o, o) - r * r;
  float disc = b * b - c;
  if (disc < 0.0) return vec2(-1.0);
  float root = sqrt(disc);
  return vec2(-b - root, -b + root);
}

void main() {
  vec4 far = uInverseViewProjection * vec4(vNdc, 0.0001, 1.0);
  vec3 d = normalize(far.xyz / far.w);
  vec2 shell = sphere(uEye, d, uGroundRadius + kAtmosphereThickness);
  vec3 space = vec3(0.002, 0.003, 0.010);
  vec3 colour = space;
  if (shell.y > 0.0) {
    float start = max(shell.x, 0.0);
    float end = shell.y;
    vec2 ground = sphere(uEye, d, uGroundRadius);
    if (ground.x > 0.0) end = min(end, ground.x);
    float path = max(end - start, 0.0);
    float optical = path / kHorizontalPath;
    vec3 middle = uEye + d * (0.5 * (start + end));
    float daylight = smoothstep(-0.15, 0.25, dot(normalize(middle), uSunEcef));
    vec3 zenith = vec3(0.11, 0.26, 0.62), horizon = vec3(0.62, 0.74, 0.90);
    vec3 sky = mix(zenith, horizon, smoothstep(0.15, 1.0, optical));
    colour = mix(space, sky * daylight + space, 1.0 - exp(-12.0 * optical));
  }
  colour = clamp(colour, 0.0, 1.0);
  fragColour = vec4(mix(colour * 12.92, 1.055 * pow(colour, vec3(1.0 / 2.4)) - 0.055,
                        step(vec3(0.0031308), colour)), 1.0);
}
