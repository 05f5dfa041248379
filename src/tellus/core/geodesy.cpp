#include "tellus/core/geodesy.hpp"

#include <cmath>

namespace tellus::wgs84 {

double meridianRadius(double latRad) {
  const double s = std::sin(latRad);
  const double w = 1.0 - kEccentricitySq * s * s;
  return kSemiMajorAxisM * (1.0 - kEccentricitySq) / (w * std::sqrt(w));
}

double primeVerticalRadius(double latRad) {
  const double s = std::sin(latRad);
  return kSemiMajorAxisM / std::sqrt(1.0 - kEccentricitySq * s * s);
}

double northSouthMetres(double latRad, double dLatRad) {
  return meridianRadius(latRad) * dLatRad;
}

double eastWestMetres(double latRad, double dLonRad) {
  return primeVerticalRadius(latRad) * std::cos(latRad) * dLonRad;
}

}  // namespace tellus::wgs84

namespace tellus::wgs84 {

LatitudeTerms LatitudeTerms::of(double latRad) {
  return {std::sin(latRad), std::cos(latRad), wgs84::primeVerticalRadius(latRad)};
}

glm::dvec3 geodeticToEcef(const LatitudeTerms& latitude, double cosLon, double sinLon,
                          double heightM) {
  const double n = latitude.primeVerticalRadius;
  const double horizontal = (n + heightM) * latitude.cosLat;
  return {horizontal * cosLon, horizontal * sinLon,
          (n * (1.0 - kEccentricitySq) + heightM) * latitude.sinLat};
}

glm::dvec3 geodeticToEcef(const Geodetic& point) {
  return geodeticToEcef(LatitudeTerms::of(point.latRad), std::cos(point.lonRad),
                        std::sin(point.lonRad), point.heightM);
}

Geodetic ecefToGeodetic(const glm::dvec3& ecef) {
  constexpr double a2 = kSemiMajorAxisM * kSemiMajorAxisM;
  constexpr double e2 = kEccentricitySq;
  constexpr double e4 = e2 * e2;
  const double horizontalSq = ecef.x * ecef.x + ecef.y * ecef.y;
  const double horizontal = std::sqrt(horizontalSq);
  Geodetic out;
  out.lonRad = std::atan2(ecef.y, ecef.x);
  const double p = horizontalSq / a2;
  const double q = (1.0 - e2) / a2 * ecef.z * ecef.z;
  const double r = (p + q - e4) / 6.0;
  if (r <= 0.0) {  // within a * e^2 (~43 km) of the centre, where the formula breaks down
    out.latRad = ecef.z >= 0.0 ? kDegree * 90.0 : -kDegree * 90.0;
    out.heightM = std::abs(ecef.z) - kSemiMinorAxisM;
    return out;
  }
  const double s = e4 * p * q / (4.0 * r * r * r);
  const double t = std::cbrt(1.0 + s + std::sqrt(s * (2.0 + s)));
  const double u = r * (1.0 + t + 1.0 / t);
  const double v = std::sqrt(u * u + e4 * q);
  const double w = e2 * (u + v - q) / (2.0 * v);
  const double k = std::sqrt(u + v + w * w) - w;
  const double d = k * horizontal / (k + e2);
  const double dz = std::hypot(d, ecef.z);
  out.latRad = 2.0 * std::atan2(ecef.z, d + dz);
  out.heightM = (k + e2 - 1.0) / k * dz;
  return out;
}

}  // namespace tellus::wgs84
