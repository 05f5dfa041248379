#include "tellus/eval/store_surface.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include <glm/geometric.hpp>

#include "tellus/core/geodesy.hpp"

namespace tellus {
namespace {

// Decoded tiles kept at most (257^2 floats each: about 68 MB), then all dropped: a frame meets
// a few hundred at most, and consecutive frames mostly the same ones.
constexpr std::size_t kCachedTiles = 256;

}  // namespace

StoreSurface::StoreSurface(std::shared_ptr<const GlobalStore> store, const Geoid* geoid)
    : store_(std::move(store)), geoid_(geoid),
      depth_(store_->metadata().deepestDepth), cells_(store_->tileCells()) {}

const std::vector<float>* StoreSurface::storedTile(GeoTileKey stored) {
  auto it = tiles_.find(stored);
  if (it != tiles_.end()) return &it->second;
  if (tiles_.size() >= kCachedTiles) tiles_.clear();
  std::vector<float> heights(store_->tileShape().sampleCount());
  if (!store_->readTileMetres(stored, heights)) return nullptr;
  return &tiles_.emplace(stored, std::move(heights)).first->second;
}

bool StoreSurface::sampleHeight(GeoTileKey key, int column, int row, double& heightM) {
  // A vertex on a tile edge belongs to every tile that meets there: the store's rule picks
  // its source (the deepest among them), as readGlobalRegion fills the reference's grid.
  const StoreSampleSource at = storeSampleSource(*store_, key, column, row);
  const std::vector<float>* heights = storedTile(at.source);
  if (!heights) return false;
  heightM = tileSurfaceAt(*heights, cells_, at.u, at.v);
  return true;
}

glm::dvec3 StoreSurface::vertex(GeoTileKey key, int column, int row, double heightM) const {
  const double latDeg = GlobalTiling::sampleLatDeg(key, cells_, row);
  const double lonDeg = GlobalTiling::sampleLonDeg(key, cells_, column);
  const double n = geoid_ ? geoid_->undulationM(latDeg, lonDeg) : 0.0;
  return wgs84::geodeticToEcef({latDeg * wgs84::kDegree, lonDeg * wgs84::kDegree, heightM + n});
}

bool StoreSurface::trueSurfacePoint(const glm::dvec3& drawn, glm::dvec3& surface) {
  const wgs84::Geodetic g = wgs84::ecefToGeodetic(drawn);
  const double latDeg = g.latRad / wgs84::kDegree, lonDeg = g.lonRad / wgs84::kDegree;
  const GeoTileKey key = GlobalTiling::tileAt(depth_, latDeg, lonDeg);
  const GeoBounds b = GlobalTiling::bounds(key);
  const double step = GlobalTiling::tileSizeDeg(depth_) / cells_;
  double east = lonDeg - b.westDeg;
  if (east < -180.0) east += 360.0;  // a longitude given the other way round the seam
  const double col = std::clamp(east / step, 0.0, double(cells_));
  const double row = std::clamp((b.northDeg - latDeg) / step, 0.0, double(cells_));
  const int i = std::min(int(col), cells_ - 1), j = std::min(int(row), cells_ - 1);
  const double u = col - i, v = row - j;
  // North-east to south-west diagonal (grid_index_buffers.hpp).
  const int ti = u + v <= 1.0 ? i : i + 1, tj = u + v <= 1.0 ? j : j + 1;
  double hNe = 0.0, hSw = 0.0, hThird = 0.0;
  if (!sampleHeight(key, i + 1, j, hNe) || !sampleHeight(key, i, j + 1, hSw) ||
      !sampleHeight(key, ti, tj, hThird)) {
    return false;
  }
  const glm::dvec3 ne = vertex(key, i + 1, j, hNe), sw = vertex(key, i, j + 1, hSw);
  const glm::dvec3 third = vertex(key, ti, tj, hThird);
  const glm::dvec3 normal{std::cos(g.latRad) * std::cos(g.lonRad),
                          std::cos(g.latRad) * std::sin(g.lonRad), std::sin(g.latRad)};
  const glm::dvec3 planeNormal = glm::cross(sw - ne, third - ne);
  const double denominator = glm::dot(normal, planeNormal);
  // A cell at a pole degenerates (its northern samples are one point): no plane there.
  if (std::abs(denominator) < 1e-12 * glm::dot(planeNormal, planeNormal)) return false;
  const double t = glm::dot(ne - drawn, planeNormal) / denominator;
  surface = drawn + t * normal;
  return true;
}

TrueSurfaceFn StoreSurface::truth() {
  return [this](const glm::dvec3& drawn, glm::dvec3& surface) {
    return trueSurfacePoint(drawn, surface);
  };
}

double StoreSurface::ellipsoidalHeightM(double latDeg, double lonDeg) {
  const glm::dvec3 onEllipsoid =
      wgs84::geodeticToEcef({latDeg * wgs84::kDegree, lonDeg * wgs84::kDegree, 0.0});
  glm::dvec3 surface;
  if (!trueSurfacePoint(onEllipsoid, surface)) return std::numeric_limits<double>::quiet_NaN();
  return wgs84::ecefToGeodetic(surface).heightM;
}

}  // namespace tellus
