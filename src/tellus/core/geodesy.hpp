#pragma once
// WGS84 ellipsoid quantities (double precision). Angles in radians, lengths in metres.

namespace tellus::wgs84 {

inline constexpr double kSemiMajorAxisM = 6378137.0;
inline constexpr double kFlattening = 1.0 / 298.257223563;
inline constexpr double kEccentricitySq = kFlattening * (2.0 - kFlattening);

// Radius of curvature in the meridian (north-south) at geodetic latitude lat.
double meridianRadius(double latRad);
// Radius of curvature in the prime vertical (east-west) at geodetic latitude lat.
double primeVerticalRadius(double latRad);

// Ground distances of small steps: metres covered by dLat / dLon radians at latitude lat.
double northSouthMetres(double latRad, double dLatRad);
double eastWestMetres(double latRad, double dLonRad);

}  // namespace tellus::wgs84
