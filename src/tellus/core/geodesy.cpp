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
