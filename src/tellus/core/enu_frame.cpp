#include "tellus/core/enu_frame.hpp"

#include <cmath>

#include <glm/geometric.hpp>

namespace tellus {

EnuAxes EnuAxes::at(double latRad, double lonRad) {
  const double sinLat = std::sin(latRad), cosLat = std::cos(latRad);
  const double sinLon = std::sin(lonRad), cosLon = std::cos(lonRad);
  return {{-sinLon, cosLon, 0.0},
          {-sinLat * cosLon, -sinLat * sinLon, cosLat},
          {cosLat * cosLon, cosLat * sinLon, sinLat}};
}

EnuFrame::EnuFrame(const wgs84::Geodetic& origin) : originEcef_(wgs84::geodeticToEcef(origin)) {
  const EnuAxes axes = EnuAxes::at(origin.latRad, origin.lonRad);
  east_ = axes.east;
  north_ = axes.north;
  up_ = axes.up;
}

glm::dvec3 EnuFrame::toEnu(const glm::dvec3& ecef) const {
  const glm::dvec3 d = ecef - originEcef_;
  return {glm::dot(d, east_), glm::dot(d, north_), glm::dot(d, up_)};
}

glm::dvec3 EnuFrame::toEcef(const glm::dvec3& enu) const {
  return originEcef_ + directionToEcef(enu);
}

glm::dvec3 EnuFrame::directionToEcef(const glm::dvec3& enu) const {
  return east_ * enu.x + north_ * enu.y + up_ * enu.z;
}

}  // namespace tellus
