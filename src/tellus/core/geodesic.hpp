#pragma once
// Geodesics on the WGS84 ellipsoid: the shortest path between two points, through PROJ's
// implementation of Karney's algorithms (geodesic.h; accurate to nanometres), not re-derived.
// Degrees in and out, metres.
namespace tellus {

struct GeodesicInverse {
  double distanceM = 0.0;
  double azimuth1Deg = 0.0;  // at the first point, clockwise from north
  double azimuth2Deg = 0.0;  // at the second point (forward direction)
};

GeodesicInverse geodesicInverse(double lat1Deg, double lon1Deg, double lat2Deg, double lon2Deg);

struct GeodesicPoint {
  double latDeg = 0.0, lonDeg = 0.0, azimuthDeg = 0.0;
};

// The point `distanceM` along the geodesic leaving (lat, lon) at `azimuthDeg`.
GeodesicPoint geodesicDirect(double latDeg, double lonDeg, double azimuthDeg, double distanceM);

}  // namespace tellus
