#include "tellus/eval/globe_surface.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include <glm/geometric.hpp>

#include "tellus/core/geodesy.hpp"
#include "tellus/lod/globe/globe_mesh.hpp"

namespace tellus {

GlobeSurface::GlobeSurface(const HeightGrid& grid, const Geoid* geoid)
    : grid_(grid), geoid_(geoid) {
  const double stepLon = grid.georef.geoTransform[1];
  wraps_ = std::abs(grid.width * stepLon - 360.0) < 1e-6 * 360.0;  // as buildGlobeMesh
  columns_ = grid.width + (wraps_ ? 1 : 0);
  const HeightRange range = grid.heightRange();
  highestM_ = double(range.maxM) + (geoid ? 107.0 : 0.0);  // EGM96's largest undulation
}

// The reference's vertex (col, row), exactly as buildGlobeMesh computes it.
glm::dvec3 GlobeSurface::vertex(int col, int row) const {
  const double lat =
      std::clamp(globe::sampleLatitudeDeg(grid_, row), -90.0, 90.0) * wgs84::kDegree;
  const double lon = globe::sampleLongitudeDeg(grid_, col) * wgs84::kDegree;
  const double n = geoid_ ? geoid_->undulationM(lat / wgs84::kDegree, lon / wgs84::kDegree) : 0.0;
  return wgs84::geodeticToEcef({lat, lon, double(grid_.at(col % grid_.width, row)) + n});
}

bool GlobeSurface::trueSurfacePoint(const glm::dvec3& drawn, glm::dvec3& surface) const {
  const wgs84::Geodetic g = wgs84::ecefToGeodetic(drawn);
  const auto& gt = grid_.georef.geoTransform;
  const double latDeg = g.latRad / wgs84::kDegree, lonDeg = g.lonRad / wgs84::kDegree;
  double row = (latDeg - (gt[3] + 0.5 * gt[5])) / gt[5];
  double col = (lonDeg - (gt[0] + 0.5 * gt[1])) / gt[1];
  if (wraps_) {
    col = std::fmod(col, double(grid_.width));
    if (col < 0.0) col += grid_.width;
  } else if (col < -0.5 && gt[0] + 0.5 * gt[1] > 0.0) {
    col += 360.0 / gt[1];  // a grid given in 0..360 longitudes
  }
  // A vertex on the grid's last row or column may land a rounding error outside.
  constexpr double kSlack = 1e-7;
  if (!(row >= -kSlack && row <= grid_.height - 1 + kSlack && col >= -kSlack &&
        col <= columns_ - 1 + kSlack)) {
    return false;
  }
  row = std::clamp(row, 0.0, double(grid_.height - 1));
  col = std::clamp(col, 0.0, double(columns_ - 1));
  const int i = std::min(int(col), columns_ - 2), j = std::min(int(row), grid_.height - 2);
  const double u = col - i, v = row - j;
  // North-east to south-west diagonal (grid_index_buffers.hpp).
  const glm::dvec3 ne = vertex(i + 1, j), sw = vertex(i, j + 1);
  const glm::dvec3 third = u + v <= 1.0 ? vertex(i, j) : vertex(i + 1, j + 1);
  const glm::dvec3 normal{std::cos(g.latRad) * std::cos(g.lonRad),
                          std::cos(g.latRad) * std::sin(g.lonRad), std::sin(g.latRad)};
  const glm::dvec3 planeNormal = glm::cross(sw - ne, third - ne);
  const double denominator = glm::dot(normal, planeNormal);
  if (std::abs(denominator) < 1e-12 * glm::dot(planeNormal, planeNormal)) return false;
  const double t = glm::dot(ne - drawn, planeNormal) / denominator;
  surface = drawn + t * normal;
  return true;
}

TrueSurfaceFn GlobeSurface::truth() const {
  return [this](const glm::dvec3& drawn, glm::dvec3& surface) {
    return trueSurfacePoint(drawn, surface);
  };
}

double GlobeSurface::ellipsoidalHeightM(double latDeg, double lonDeg) const {
  const glm::dvec3 onEllipsoid =
      wgs84::geodeticToEcef({latDeg * wgs84::kDegree, lonDeg * wgs84::kDegree, 0.0});
  glm::dvec3 surface;
  if (!trueSurfacePoint(onEllipsoid, surface)) return std::numeric_limits<double>::quiet_NaN();
  return wgs84::ecefToGeodetic(surface).heightM;
}

}  // namespace tellus
