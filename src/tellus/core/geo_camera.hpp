#pragma once
// A camera on the globe: where (latitude, longitude, altitude above the WGS84 ellipsoid) and
// which way (heading clockwise from north, pitch above the local horizon, vertical field of
// view), turned into a ViewSetup in ECEF (geodesy.hpp) so that the harness's projections and
// unprojections work unchanged. As for flat cameras, the view matrix is a pure rotation: GPU
// positions are relative to the eye, so nothing is ever large in float.
//
// In the returned ViewSetup, camera.position is the eye in ECEF and camera.yawDeg/pitchDeg are
// the heading and pitch; Camera::forward()/right()/up() describe a flat z-up world and do not
// apply: use GeoCameraFrame.
#include <optional>
#include <string_view>

#include <glm/vec2.hpp>

#include <glm/vec3.hpp>

#include "tellus/core/camera.hpp"
#include "tellus/core/result.hpp"

namespace tellus {

struct GeoCamera {
  double latDeg = 0.0;
  double lonDeg = 0.0;
  double altitudeM = 1000.0;  // above the ellipsoid
  double headingDeg = 0.0;    // 0 north, 90 east
  double pitchDeg = 0.0;      // above the local horizon; -90 straight down
  double fovYDeg = 45.0;
};

// Latitude in [-90, 90], finite longitude within +-1e6 degrees, altitude from -12 km to a
// million kilometres, pitch in [-90, 90], heading finite within +-1e6, field of view in
// [0.01, 179]. The error names the value.
Status checkGeoCamera(const GeoCamera& camera);
// "lat,lon,altitude,heading,pitch,fov" (degrees and metres).
Result<GeoCamera> parseGeoCamera(std::string_view text);

// The eye in ECEF and its orthonormal axes: forward (the view direction), right (horizontal)
// and up = right x forward.
struct GeoCameraFrame {
  glm::dvec3 eye{0.0};
  glm::dvec3 forward{0.0}, right{0.0}, up{0.0};
};
GeoCameraFrame geoCameraFrame(const GeoCamera& camera);

// Near and far for a globe view: near half the eye's clearance above `groundHeightM` (the
// terrain under it, ellipsoidal; at least 0.5 m), far the distance to the horizon plus the
// distance beyond it at which terrain up to `highestTerrainM` can still rise into view.
ClipRange chooseGeoClipRange(const GeoCamera& camera, double groundHeightM,
                             double highestTerrainM);

ViewSetup geoViewSetup(const GeoCamera& camera, const ClipRange& clip, int width, int height);

// The latitude/longitude box of the ground a view can show: rays through a grid of image
// points (aspect = width / height) meet the ellipsoid, or, where they pass above the horizon,
// reach as far as terrain up to `highestTerrainM` could rise into view behind it. A box that
// would cross the antimeridian or reach within a degree of a pole spans all longitudes;
// west < east always.
struct GeoFootprint {
  double westDeg = -180.0, southDeg = -90.0, eastDeg = 180.0, northDeg = 90.0;
};
GeoFootprint geoViewFootprint(const GeoCamera& camera, double aspect, double highestTerrainM);

// Latitude and longitude (degrees, x = lat, y = lon) where the ray through `pixel` (x right, y
// down) of a globe view meets the ellipsoid; nothing when it passes beside the Earth.
std::optional<glm::dvec2> ellipsoidUnderPixel(const ViewSetup& view, const glm::dvec2& pixel);

}  // namespace tellus
