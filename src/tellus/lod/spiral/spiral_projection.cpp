#include "tellus/lod/spiral/spiral_projection.hpp"

#include <algorithm>
#include <cmath>

#include "tellus/core/geodesy.hpp"

namespace tellus {
namespace {

constexpr float kSemiMajorM = float(wgs84::kSemiMajorAxisM);
constexpr float kE2 = float(wgs84::kEccentricitySq);
constexpr float kSeriesBelow = 0.25f;  // radians: sin, 1 - cos and tanh by their series below

// atan2(y, x), accurate relative to its size when |y| << x (series), as the shader's.
float spiralAtan2(float y, float x) {
  if (x > 0.0f && std::abs(y) < 0.125f * x) {
    const float t = y / x, t2 = t * t;
    return t * (1.0f - t2 * (1.0f / 3.0f - t2 * (1.0f / 5.0f - t2 * (1.0f / 7.0f - t2 / 9.0f))));
  }
  return std::atan2(y, x);
}

// tanh r for r >= 0, relative to its size near 0.
float spiralTanh(float r) {
  if (r < kSeriesBelow) {
    const float r2 = r * r;
    return r * (1.0f - r2 * (1.0f / 3.0f - r2 * (2.0f / 15.0f - r2 * (17.0f / 315.0f))));
  }
  return std::tanh(r);
}

// (x, y, (1 - e^2) z): the ellipsoid's scaling of a normal into a position over N.
glm::vec3 flattenZ(glm::vec3 v) {
  return {v.x, v.y, (1.0f - kE2) * v.z};
}

}  // namespace

std::string_view spiralProjectionName(SpiralProjection projection) {
  switch (projection) {
    case SpiralProjection::Globe: return "globe";
    case SpiralProjection::Flat: return "flat";
    case SpiralProjection::Hyperbolic: return "hyperbolic";
    case SpiralProjection::Dome: return "dome";
  }
  return "globe";
}

std::optional<SpiralProjection> parseSpiralProjection(std::string_view name) {
  for (SpiralProjection p : {SpiralProjection::Globe, SpiralProjection::Flat,
                             SpiralProjection::Hyperbolic, SpiralProjection::Dome}) {
    if (spiralProjectionName(p) == name) return p;
  }
  return std::nullopt;
}

SpiralFocus makeSpiralFocus(double latRad, double lonRad) {
  SpiralFocus focus;
  focus.latRad = latRad;
  focus.lonRad = lonRad;
  const double sinLat = std::sin(latRad), cosLat = std::cos(latRad);
  const double sinLon = std::sin(lonRad), cosLon = std::cos(lonRad);
  focus.up = glm::vec3(float(cosLat * cosLon), float(cosLat * sinLon), float(sinLat));
  focus.east = glm::vec3(float(-sinLon), float(cosLon), 0.0f);
  focus.north = glm::vec3(float(-sinLat * cosLon), float(-sinLat * sinLon), float(cosLat));
  focus.sinLat = float(sinLat);
  focus.cosLat = float(cosLat);
  const double w = 1.0 - wgs84::kEccentricitySq * sinLat * sinLat;
  focus.primeVerticalM = float(wgs84::kSemiMajorAxisM / std::sqrt(w));
  focus.meridianM =
      float(wgs84::kSemiMajorAxisM * (1.0 - wgs84::kEccentricitySq) / (w * std::sqrt(w)));
  return focus;
}

float spiralCorrectedRadius(float radius, float minRadius, float maxRadius, bool correct) {
  if (!correct || !(maxRadius > minRadius)) return radius;
  const float span = maxRadius - minRadius;
  const float t = std::clamp((radius - minRadius) / span, 0.0f, 1.0f);
  // Beyond maxRadius (the last revolution's outer edge) the radius grows as it was.
  return radius > maxRadius ? radius : std::sqrt(t) * span + minRadius;
}

float spiralSinRadius(float radius) {
  if (radius < kSeriesBelow) {
    const float r2 = radius * radius;
    return radius * (1.0f - r2 / 6.0f * (1.0f - r2 / 20.0f * (1.0f - r2 / 42.0f)));
  }
  return std::sin(radius);
}

float spiralOneMinusCosRadius(float radius) {
  if (radius < kSeriesBelow) {
    const float r2 = radius * radius;
    return 0.5f * r2 * (1.0f - r2 / 12.0f * (1.0f - r2 / 30.0f * (1.0f - r2 / 56.0f)));
  }
  return 1.0f - std::cos(radius);
}

glm::vec2 spiralLatLonOffset(glm::vec2 direction, float radius, const SpiralFocus& focus) {
  const float sinR = spiralSinRadius(radius);
  const float cosR = 1.0f - spiralOneMinusCosRadius(radius);
  // p in the focal meridian's frame: along the meridian's horizontal, east, and z.
  const float along = cosR * focus.cosLat - sinR * direction.y * focus.sinLat;
  const float east = sinR * direction.x;
  const float q = std::sqrt(along * along + east * east);  // |p| off the axis
  // q - along, without the difference when along > 0.
  const float dq = (along > 0.0f) ? east * east / (q + along) : q - along;
  const float dLat = spiralAtan2(sinR * direction.y - focus.sinLat * dq, cosR + focus.cosLat * dq);
  const float dLon = spiralAtan2(east, along);
  return {dLat, dLon};
}

glm::vec3 spiralNormal(glm::vec2 direction, float radius, const SpiralFocus& focus) {
  const float sinR = spiralSinRadius(radius);
  const float oneMinusCos = spiralOneMinusCosRadius(radius);
  return focus.up * (1.0f - oneMinusCos) +
         sinR * (direction.x * focus.east + direction.y * focus.north);
}

glm::vec3 spiralGlobeOffset(glm::vec2 direction, float radius, float heightM,
                            const SpiralFocus& focus) {
  const float sinR = spiralSinRadius(radius);
  const float oneMinusCos = spiralOneMinusCosRadius(radius);
  // p - f, exactly and from small quantities.
  const glm::vec3 d =
      -oneMinusCos * focus.up + sinR * (direction.x * focus.east + direction.y * focus.north);
  const glm::vec3 p = focus.up + d;
  // N(p) - N(f) = a (1/sqrt(wp) - 1/sqrt(wf)), w = 1 - e^2 sin^2 lat, without the difference.
  const float sf = focus.sinLat, sp = sf + d.z;
  const float wf = 1.0f - kE2 * sf * sf, wp = 1.0f - kE2 * sp * sp;
  const float kf = 1.0f / std::sqrt(wf), kp = 1.0f / std::sqrt(wp);
  const float dPrimeVertical = kSemiMajorM * kE2 * d.z * (sp + sf) / (wf * wp * (kp + kf));
  // X(p, h) - X(f, 0) = N(f) D(p - f) + (N(p) - N(f)) D(p) + h p, D = diag(1, 1, 1 - e^2).
  return focus.primeVerticalM * flattenZ(d) + dPrimeVertical * flattenZ(p) + heightM * p;
}

glm::vec3 spiralProjectedOffset(SpiralProjection projection, glm::vec2 direction, float radius,
                                glm::vec2 latLonOffset, float heightM, const SpiralFocus& focus) {
  const glm::vec3 horizontal = direction.x * focus.east + direction.y * focus.north;
  const float gaussianM = std::sqrt(focus.meridianM * focus.primeVerticalM);
  switch (projection) {
    case SpiralProjection::Globe:
      return spiralGlobeOffset(direction, radius, heightM, focus);
    case SpiralProjection::Flat:
      return focus.primeVerticalM * focus.cosLat * latLonOffset.y * focus.east +
             focus.meridianM * latLonOffset.x * focus.north + heightM * focus.up;
    case SpiralProjection::Hyperbolic:
      return gaussianM * spiralTanh(radius) * horizontal + heightM * focus.up;
    case SpiralProjection::Dome:
      return gaussianM * spiralSinRadius(radius) * horizontal +
             (gaussianM * spiralOneMinusCosRadius(radius) + heightM) * focus.up;
  }
  return spiralGlobeOffset(direction, radius, heightM, focus);
}

}  // namespace tellus
