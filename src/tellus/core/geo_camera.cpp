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
