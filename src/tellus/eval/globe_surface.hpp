#pragma once
// The globe's ground truth for the harness: the surface the globe reference draws from a
// latitude/longitude grid (globe::buildGlobeMesh: every sample on the ellipsoid at H + N, two
// planar triangles a cell split from north-east to south-west), queried in ECEF. GL-free.
//
// trueSurfacePoint() is the TrueSurfaceFn of frame_metrics.hpp on the globe: a drawn point is
// moved along the ellipsoid's normal at its latitude/longitude onto the reference triangle
// there, i.e. the point of the true surface at the same latitude and longitude.
#include <glm/vec3.hpp>

#include "tellus/dem/geoid.hpp"
#include "tellus/dem/height_grid.hpp"
#include "tellus/eval/frame_metrics.hpp"

namespace tellus {

class GlobeSurface {
 public:
  // `grid` must be a geographic grid (as for buildGlobeMesh); both it and `geoid` (may be null:
  // heights are then ellipsoidal) must outlive this object.
  GlobeSurface(const HeightGrid& grid, const Geoid* geoid);

  // False outside the grid's samples.
  bool trueSurfacePoint(const glm::dvec3& drawnEcef, glm::dvec3& surfaceEcef) const;
  TrueSurfaceFn truth() const;
  // The surface's height above the ellipsoid at (lat, lon), metres; NaN outside the grid.
  double ellipsoidalHeightM(double latDeg, double lonDeg) const;
  // The highest ellipsoidal height of any sample (for clip ranges).
  double highestM() const { return highestM_; }
  bool wrapsLongitude() const { return wraps_; }

 private:
  glm::dvec3 vertex(int col, int row) const;

  const HeightGrid& grid_;
  const Geoid* geoid_;
  bool wraps_ = false;
  int columns_ = 0;
  double highestM_ = 0.0;
};

}  // namespace tellus
