#pragma once
// WGS84 ellipsoid quantities and conversions (double precision). Angles in radians, lengths in
// metres. Heights here are ellipsoidal; heights above the geoid (SRTM, ETOPO) become ellipsoidal
// by adding the geoid undulation (tellus/dem/geoid.hpp).
//
// ECEF (earth-centred, earth-fixed): x towards (lat 0, lon 0), y towards (0, 90 E), z towards the
// north pole. The conversions are this project's own code because they run per vertex and per
// pixel; tests/unit/geodesy_test.cpp checks them against PROJ (+proj=cart) on a million points.
#include <glm/vec3.hpp>

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

inline constexpr double kSemiMinorAxisM = kSemiMajorAxisM * (1.0 - kFlattening);

struct Geodetic {
  double latRad = 0.0;  // geodetic latitude, -pi/2 .. pi/2
  double lonRad = 0.0;  // longitude, east positive
  double heightM = 0.0;  // above the ellipsoid
};

glm::dvec3 geodeticToEcef(const Geodetic& point);

// geodeticToEcef in two parts, for grids of many points on few parallels and meridians (a
// mesh's rows and columns): a latitude's terms once per row, a longitude's sine and cosine once
// per column. The same operations in the same order: the same bits as geodeticToEcef.
struct LatitudeTerms {
  double sinLat = 0.0, cosLat = 1.0;
  double primeVerticalRadius = kSemiMajorAxisM;
  static LatitudeTerms of(double latRad);
};
glm::dvec3 geodeticToEcef(const LatitudeTerms& latitude, double cosLon, double sinLon,
                          double heightM);
// Exact closed form (Vermeille 2004, "Computing geodetic coordinates from geocentric
// coordinates"), valid everywhere except within about 43 km of the Earth's centre (returned as
// the nearest pole's latitude there). Longitude in (-pi, pi].
Geodetic ecefToGeodetic(const glm::dvec3& ecef);

// Degrees <-> radians, for the many places that read and print degrees.
inline constexpr double kDegree = 3.14159265358979323846 / 180.0;

}  // namespace tellus::wgs84
