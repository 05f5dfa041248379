// The spiral globe's projections (seed 001): the GLSL twin of
// src/tellus/lod/spiral/spiral_projection.cpp, function for function and name for name (read
// that file's header for the geometry and the precision argument). Keep the two in step: the
// GPU tests compare them.

struct SpiralFocus {
  vec3 east, north, up;   // the focal point's frame, unit ECEF
  float sinLat, cosLat;
  float primeVerticalM;   // N
  float meridianM;        // M
};

const float kSpiralSemiMajorM = 6378137.0;
const float kSpiralE2 = 0.00669437999014;
const float kSpiralSeriesBelow = 0.25;

float spiralAtan2(float y, float x) {
  if (x > 0.0 && abs(y) < 0.125 * x) {
    float t = y / x, t2 = t * t;
    return t * (1.0 - t2 * (1.0 / 3.0 - t2 * (1.0 / 5.0 - t2 * (1.0 / 7.0 - t2 / 9.0))));
  }
  return atan(y, x);
}

float spiralTanh(float r) {
  if (r < kSpiralSeriesBelow) {
    float r2 = r * r;
    return r * (1.0 - r2 * (1.0 / 3.0 - r2 * (2.0 / 15.0 - r2 * (17.0 / 315.0))));
  }
  return tanh(r);
}

vec3 spiralFlattenZ(vec3 v) {
  return vec3(v.x, v.y, (1.0 - kSpiralE2) * v.z);
}

float spiralCorrectedRadius(float radius, float minRadius, float maxRadius, bool correct) {
  if (!correct || !(maxRadius > minRadius)) return radius;
  float span = maxRadius - minRadius;
  float t = clamp((radius - minRadius) / span, 0.0, 1.0);
  return radius > maxRadius ? radius : sqrt(t) * span + minRadius;
}

float spiralSinRadius(float radius) {
  if (radius < kSpiralSeriesBelow) {
    float r2 = radius * radius;
    return radius * (1.0 - r2 / 6.0 * (1.0 - r2 / 20.0 * (1.0 - r2 / 42.0)));
  }
  return sin(radius);
}

float spiralOneMinusCosRadius(float radius) {
  if (radius < kSpiralSeriesBelow) {
    float r2 = radius * radius;
    return 0.5 * r2 * (1.0 - r2 / 12.0 * (1.0 - r2 / 30.0 * (1.0 - r2 / 56.0)));
  }
  return 1.0 - cos(radius);
}

vec2 spiralLatLonOffset(vec2 direction, float radius, SpiralFocus focus) {
  float sinR = spiralSinRadius(radius);
  float cosR = 1.0 - spiralOneMinusCosRadius(radius);
  float along = cosR * focus.cosLat - sinR * direction.y * focus.sinLat;
  float east = sinR * direction.x;
  float q = sqrt(along * along + east * east);
  float dq = (along > 0.0) ? east * east / (q + along) : q - along;
  float dLat = spiralAtan2(sinR * direction.y - focus.sinLat * dq, cosR + focus.cosLat * dq);
  float dLon = spiralAtan2(east, along);
  return vec2(dLat, dLon);
}

vec3 spiralNormal(vec2 direction, float radius, SpiralFocus focus) {
  float sinR = spiralSinRadius(radius);
  float oneMinusCos = spiralOneMinusCosRadius(radius);
  return focus.up * (1.0 - oneMinusCos) + sinR * (direction.x * focus.east + direction.y * focus.north);
}

vec3 spiralGlobeOffset(vec2 direction, float radius, float heightM, SpiralFocus focus) {
  float sinR = spiralSinRadius(radius);
  float oneMinusCos = spiralOneMinusCosRadius(radius);
  vec3 d = -oneMinusCos * focus.up + sinR * (direction.x * focus.east + direction.y * focus.north);
  vec3 p = focus.up + d;
  float sf = focus.sinLat, sp = sf + d.z;
  float wf = 1.0 - kSpiralE2 * sf * sf, wp = 1.0 - kSpiralE2 * sp * sp;
  float kf = 1.0 / sqrt(wf), kp = 1.0 / sqrt(wp);
  float dPrimeVertical = kSpiralSemiMajorM * kSpiralE2 * d.z * (sp + sf) / (wf * wp * (kp + kf));
  return focus.primeVerticalM * spiralFlattenZ(d) + dPrimeVertical * spiralFlattenZ(p) + heightM * p;
}

// projection: 0 globe, 1 flat, 2 hyperbolic, 3 dome (SpiralProjection).
vec3 spiralProjectedOffset(int projection, vec2 direction, float radius, vec2 latLonOffset,
                           float heightM, SpiralFocus focus) {
  vec3 horizontal = direction.x * focus.east + direction.y * focus.north;
  float gaussianM = sqrt(focus.meridianM * focus.primeVerticalM);
  if (projection == 1) {
    return focus.primeVerticalM * focus.cosLat * latLonOffset.y * focus.east +
           focus.meridianM * latLonOffset.x * focus.north + heightM * focus.up;
  }
  if (projection == 2) return gaussianM * spiralTanh(radius) * horizontal + heightM * focus.up;
  if (projection == 3) {
    return gaussianM * spiralSinRadius(radius) * horizontal +
           (gaussianM * spiralOneMinusCosRadius(radius) + heightM) * focus.up;
  }
  return spiralGlobeOffset(direction, radius, heightM, focus);
}
