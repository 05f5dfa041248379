#pragma once
// A local east-north-up frame on the WGS84 ellipsoid: the tangent frame at a geodetic origin,
// for cameras and local work on the globe. Metres; right-handed (east x north = up).
#include <glm/mat3x3.hpp>
#include <glm/vec3.hpp>

#include "tellus/core/geodesy.hpp"

namespace tellus {

// The east, north and up unit vectors in ECEF at a latitude and longitude (radians).
struct EnuAxes {
  glm::dvec3 east, north, up;
  static EnuAxes at(double latRad, double lonRad);
};

class EnuFrame {
 public:
  explicit EnuFrame(const wgs84::Geodetic& origin);

  const glm::dvec3& originEcef() const { return originEcef_; }
  const glm::dvec3& east() const { return east_; }
  const glm::dvec3& north() const { return north_; }
  const glm::dvec3& up() const { return up_; }  // the ellipsoid normal at the origin

  // ECEF point -> (east, north, up) offsets from the origin, and back.
  glm::dvec3 toEnu(const glm::dvec3& ecef) const;
  glm::dvec3 toEcef(const glm::dvec3& enu) const;
  // Directions only (no origin): ENU vector <-> ECEF vector.
  glm::dvec3 directionToEcef(const glm::dvec3& enu) const;
  // The rotation whose columns are east, north and up in ECEF (ECEF = R * ENU).
  glm::dmat3 rotation() const { return {east_, north_, up_}; }

 private:
  glm::dvec3 originEcef_, east_, north_, up_;
};

}  // namespace tellus
