#include "tellus/core/enu_frame.hpp"

#include <cmath>

#include <glm/geometric.hpp>

namespace tellus {

EnuFrame::EnuFrame(const wgs84::Geodetic& origin) : originEcef_(wgs84::geodeticToEcef(origin)) {
  const double sinLat = std::sin(origin.latRad), cosLat = std::cos(origin.latRad);
  const double sinLon = std::sin(origin.lonRad), cosLon = std::cos(origin.lonRad);
  east_ = {-sinLon, cosLon, 0.0};
  north_ = {-sinLat * cosLon, -sinLat * sinLon, cosLat};
  up_ = {cosLat * cosLon, cosLat * sinLon, sinLat};
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
