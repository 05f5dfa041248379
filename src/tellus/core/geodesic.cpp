#include "tellus/core/geodesic.hpp"

#include <geodesic.h>

#include "tellus/core/geodesy.hpp"

namespace tellus {
namespace {

const geod_geodesic& wgs84Geodesic() {
  static const geod_geodesic g = [] {
    geod_geodesic made;
    geod_init(&made, wgs84::kSemiMajorAxisM, wgs84::kFlattening);
    return made;
  }();
  return g;
}

}  // namespace

GeodesicInverse geodesicInverse(double lat1Deg, double lon1Deg, double lat2Deg, double lon2Deg) {
  GeodesicInverse out;
  geod_inverse(&wgs84Geodesic(), lat1Deg, lon1Deg, lat2Deg, lon2Deg, &out.distanceM,
               &out.azimuth1Deg, &out.azimuth2Deg);
  return out;
}

GeodesicPoint geodesicDirect(double latDeg, double lonDeg, double azimuthDeg, double distanceM) {
  GeodesicPoint out;
  geod_direct(&wgs84Geodesic(), latDeg, lonDeg, azimuthDeg, distanceM, &out.latDeg, &out.lonDeg,
              &out.azimuthDeg);
  return out;
}

}  // namespace tellus
