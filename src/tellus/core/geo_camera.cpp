#include "tellus/core/geo_camera.hpp"

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include <glm/geometric.hpp>

#include "tellus/core/enu_frame.hpp"
#include "tellus/core/geodesy.hpp"

namespace tellus {
namespace {

Status checkRange(const char* what, double value, double low, double high) {
  if (!std::isfinite(value) || value < low || value > high) {
    return makeError("geo camera: {} {} is outside {} to {}", what, value, low, high);
  }
  return {};
}

}  // namespace

Status checkGeoCamera(const GeoCamera& c) {
  if (Status s = checkRange("latitude", c.latDeg, -90.0, 90.0); !s) return s;
  if (Status s = checkRange("longitude", c.lonDeg, -1e6, 1e6); !s) return s;
  if (Status s = checkRange("altitude", c.altitudeM, -12000.0, 1e9); !s) return s;
  if (Status s = checkRange("heading", c.headingDeg, -1e6, 1e6); !s) return s;
  if (Status s = checkRange("pitch", c.pitchDeg, -90.0, 90.0); !s) return s;
  return checkRange("field of view", c.fovYDeg, kMinCameraFovDeg, kMaxCameraFovDeg);
}

Result<GeoCamera> parseGeoCamera(std::string_view text) {
  std::vector<double> values;
  std::size_t start = 0;
  while (start <= text.size()) {
    const std::size_t comma = std::min(text.find(',', start), text.size());
    const std::string field(text.substr(start, comma - start));
    std::size_t used = 0;
    double value = 0.0;
    try {
      value = std::stod(field, &used);
    } catch (const std::exception&) {
      used = 0;
    }
    if (used == 0 || used != field.size()) {
      return makeError("geo camera '{}': '{}' is not a number (expected lat,lon,altitude,"
                       "heading,pitch,fov)",
                       text, field);
    }
    values.push_back(value);
    start = comma + 1;
  }
  if (values.size() != 6) {
    return makeError("geo camera '{}': {} values, expected 6 (lat,lon,altitude,heading,pitch,"
                     "fov)",
                     text, values.size());
  }
  const GeoCamera camera{values[0], values[1], values[2], values[3], values[4], values[5]};
  if (Status s = checkGeoCamera(camera); !s) return s.error();
  return camera;
}

GeoCameraFrame geoCameraFrame(const GeoCamera& camera) {
  const wgs84::Geodetic where{camera.latDeg * wgs84::kDegree, camera.lonDeg * wgs84::kDegree,
                              camera.altitudeM};
  const EnuFrame enu(where);
  const double heading = camera.headingDeg * wgs84::kDegree;
  const double pitch = camera.pitchDeg * wgs84::kDegree;
  GeoCameraFrame frame;
  frame.eye = enu.originEcef();
  frame.forward = enu.directionToEcef({std::sin(heading) * std::cos(pitch),
                                       std::cos(heading) * std::cos(pitch), std::sin(pitch)});
  frame.right = enu.directionToEcef({std::cos(heading), -std::sin(heading), 0.0});
  frame.up = glm::cross(frame.right, frame.forward);
  return frame;
}

ClipRange chooseGeoClipRange(const GeoCamera& camera, double groundHeightM,
                             double highestTerrainM) {
  const glm::dvec3 eye = geoCameraFrame(camera).eye;
  // Tangent distances to a sphere of the semi-minor axis: never shorter than the true ones.
  const double b = wgs84::kSemiMinorAxisM;
  const double eyeRadius = glm::length(eye);
  const double toHorizon = eyeRadius > b ? std::sqrt(eyeRadius * eyeRadius - b * b) : 0.0;
  const double top = wgs84::kSemiMajorAxisM + std::max(highestTerrainM, 0.0);
  const double beyondHorizon = std::sqrt(top * top - b * b);
  ClipRange clip;
  clip.nearM = std::max(0.5, 0.5 * (camera.altitudeM - groundHeightM));
  clip.farM = std::max(clip.nearM * 2.0, toHorizon + beyondHorizon);
  return clip;
}

ViewSetup geoViewSetup(const GeoCamera& camera, const ClipRange& clip, int width, int height) {
  const GeoCameraFrame frame = geoCameraFrame(camera);
  ViewSetup setup;
  setup.camera.position = frame.eye;
  setup.camera.yawDeg = camera.headingDeg;
  setup.camera.pitchDeg = camera.pitchDeg;
  setup.camera.fovYDeg = camera.fovYDeg;
  setup.clip = clip;
  setup.width = width;
  setup.height = height;
  setup.view = glm::dmat4(1.0);  // rows: right, up, -forward (glm is column-major)
  for (int i = 0; i < 3; ++i) {
    setup.view[i][0] = frame.right[i];
    setup.view[i][1] = frame.up[i];
    setup.view[i][2] = -frame.forward[i];
  }
  setup.projection = reversedZProjection(camera.fovYDeg, double(width) / double(height), clip);
  setup.viewProjection = setup.projection * setup.view;
  setup.inverseViewProjection = glm::inverse(setup.viewProjection);
  return setup;
}

}  // namespace tellus

namespace tellus {
namespace {

// Distance along a ray from `origin` to the ellipsoid raised by `heightM` (axes a + h, b + h),
// or a negative number when the ray misses it.
double rayEllipsoid(const glm::dvec3& origin, const glm::dvec3& direction, double heightM) {
  const double a = wgs84::kSemiMajorAxisM + heightM, b = wgs84::kSemiMinorAxisM + heightM;
  // Scale z so that the ellipsoid becomes a sphere of radius a.
  const glm::dvec3 o{origin.x, origin.y, origin.z * a / b};
  const glm::dvec3 d{direction.x, direction.y, direction.z * a / b};
  const double qa = glm::dot(d, d), qb = 2.0 * glm::dot(o, d), qc = glm::dot(o, o) - a * a;
  const double disc = qb * qb - 4.0 * qa * qc;
  if (disc < 0.0) return -1.0;
  const double root = std::sqrt(disc);
  const double t0 = (-qb - root) / (2.0 * qa), t1 = (-qb + root) / (2.0 * qa);
  return t0 > 0.0 ? t0 : t1;
}

}  // namespace

GeoFootprint geoViewFootprint(const GeoCamera& camera, double aspect, double highestTerrainM) {
  const GeoCameraFrame frame = geoCameraFrame(camera);
  // Horizon distances on the sphere through the ground under the eye (the clip range's are
  // deliberately longer: they hold anywhere on the ellipsoid).
  const glm::dvec3 nadir = frame.eye - glm::normalize(frame.eye) * camera.altitudeM;
  const double radius = glm::length(nadir);
  const double eyeRadius = radius + std::max(camera.altitudeM, 0.0);
  const double top = radius + std::max(highestTerrainM, 0.0);
  const double farM = std::sqrt(eyeRadius * eyeRadius - radius * radius) +
                      std::sqrt(top * top - radius * radius);
  const double tanY = std::tan(0.5 * camera.fovYDeg * wgs84::kDegree);
  const double tanX = tanY * std::max(aspect, 1e-3);
  double south = 90.0, north = -90.0;
  std::vector<double> longitudes;
  const auto include = [&](const glm::dvec3& ecef) {
    const wgs84::Geodetic g = wgs84::ecefToGeodetic(ecef);
    south = std::min(south, g.latRad / wgs84::kDegree);
    north = std::max(north, g.latRad / wgs84::kDegree);
    longitudes.push_back(g.lonRad / wgs84::kDegree);
  };
  // Under the eye, whatever the view.
  include(nadir);
  constexpr int kRays = 24;
  for (int j = 0; j <= kRays; ++j) {
    for (int i = 0; i <= kRays; ++i) {
      const double x = (2.0 * i / kRays - 1.0) * tanX, y = (2.0 * j / kRays - 1.0) * tanY;
      const glm::dvec3 direction = glm::normalize(frame.forward + x * frame.right + y * frame.up);
      const double ground = rayEllipsoid(frame.eye, direction, 0.0);
      // Above the horizon: as far as terrain rising behind it can be seen, brought down to the
      // ground beneath that point.
      const double t = ground > 0.0 ? std::min(ground, farM) : farM;
      include(frame.eye + direction * t);
    }
  }
  // The ground between sampled rays (near the limb, points between two rays can lie outside
  // their box): a margin of a ray spacing, 1/24 of the span.
  const double latMargin = (north - south) / 24.0;
  south = std::max(-90.0, south - latMargin);
  north = std::min(90.0, north + latMargin);
  // A pole inside the cap the eye can see may lie between the sampled rays (the bounding box
  // of points around a pole does not hold the pole): take it in.
  const double capDeg = (std::acos(radius / eyeRadius) + std::acos(radius / top)) / wgs84::kDegree;
  if (90.0 - camera.latDeg <= capDeg) north = 90.0;
  if (90.0 + camera.latDeg <= capDeg) south = -90.0;
  GeoFootprint box;
  if (north >= 89.0 || south <= -89.0) {  // around a pole: all longitudes, up to the pole
    box.southDeg = south <= -89.0 ? -90.0 : south;
    box.northDeg = north >= 89.0 ? 90.0 : north;
    return box;
  }
  // The smallest longitude interval holding every point: the complement of the widest gap.
  std::sort(longitudes.begin(), longitudes.end());
  double widestGap = longitudes.front() + 360.0 - longitudes.back();
  double west = longitudes.front(), east = longitudes.back();
  for (std::size_t k = 1; k < longitudes.size(); ++k) {
    const double gap = longitudes[k] - longitudes[k - 1];
    if (gap > widestGap) {
      widestGap = gap;
      west = longitudes[k];
      east = longitudes[k - 1];
    }
  }
  box.southDeg = south;
  box.northDeg = north;
  const double lonMargin = (west < east ? east - west : 360.0 - (west - east)) / 24.0;
  if (west < east && west - lonMargin >= -180.0 && east + lonMargin <= 180.0) {
    box.westDeg = west - lonMargin;  // else it crosses the antimeridian: all longitudes
    box.eastDeg = east + lonMargin;
  }
  return box;
}

std::optional<glm::dvec2> ellipsoidUnderPixel(const ViewSetup& view, const glm::dvec2& pixel) {
  const glm::dvec3 eye = view.camera.position;
  const glm::dvec3 through = view.unprojectPixel(pixel, 0.5);
  const glm::dvec3 direction = glm::normalize(through - eye);
  const double t = rayEllipsoid(eye, direction, 0.0);
  if (!(t > 0.0)) return std::nullopt;
  const wgs84::Geodetic g = wgs84::ecefToGeodetic(eye + direction * t);
  return glm::dvec2(g.latRad / wgs84::kDegree, g.lonRad / wgs84::kDegree);
}

}  // namespace tellus
