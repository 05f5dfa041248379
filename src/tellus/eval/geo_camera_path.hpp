#pragma once
// Camera paths on the globe, the same for every globe renderer compared on them (the flat
// world's are in camera_path.hpp). GL-free.
//
//   descent    from 20,000 km straight down to 2 m above the target (the clearance falls
//              geometrically, 7 decades in equal steps), looking straight down until 20 km
//              above the ground, then levelling to 15 degrees down at the bottom;
//   orbit      once round the planet at 10,000 km along the great circle leaving the target
//              eastwards, looking straight down;
//   lowflight  a great-circle flight 500 m above the highest ground near its track, from
//              150 km south-west of the target over it to 150 km north-east, looking ahead
//              10 degrees down;
//   walk       2 m above the ground, 2 km east from the target, looking ahead 5 degrees down;
//   FILE.json  keyframes {"keyframes": [{"time": s, "lat": deg, "lon": deg, "alt": m,
//              "heading": deg, "pitch": deg, "fov": deg}, ...]}; alt above the ellipsoid.
//
// Between keyframes latitude, pitch and field of view are interpolated linearly, longitude and
// heading the shorter way round, and altitude geometrically when both ends are above the
// ellipsoid (a descent spans seven decades), else linearly. A path is sampled at N frames
// evenly spaced in time, first and last keyframe included.
#include <filesystem>
#include <functional>
#include <string>
#include <string_view>
#include <vector>

#include "tellus/core/geo_camera.hpp"
#include "tellus/core/result.hpp"

namespace tellus {

struct GeoCameraKeyframe {
  double timeS = 0.0;
  GeoCamera camera;
};

class GeoCameraPath {
 public:
  // At least two keyframes, strictly increasing finite times, cameras that pass checkGeoCamera.
  static Result<GeoCameraPath> fromKeyframes(std::vector<GeoCameraKeyframe> keyframes);
  const std::vector<GeoCameraKeyframe>& keyframes() const { return keyframes_; }
  GeoCamera at(double timeS) const;  // clamped to the path's times
  std::vector<GeoCamera> sample(int frames) const;

 private:
  std::vector<GeoCameraKeyframe> keyframes_;
};

// The ground's height above the ellipsoid at (lat, lon), metres; NaN where it is not known.
using GroundHeightFn = std::function<double(double latDeg, double lonDeg)>;

struct GeoPathTarget {
  double latDeg = 0.0, lonDeg = 0.0;
};

// A built-in path (names above) around `target`, or a keyframe file. Errors: an unknown name, a
// target whose ground is unknown, a bad file.
Result<GeoCameraPath> makeGeoCameraPath(std::string_view nameOrFile, const GroundHeightFn& ground,
                                        GeoPathTarget target);
std::vector<std::string_view> builtInGeoPathNames();
Result<GeoCameraPath> parseGeoCameraPath(std::string_view text, const std::string& name);
// Writes `path` as a keyframe file (the FILE.json format above) that makeGeoCameraPath() reads
// back to the same keyframes, bit for bit (JSON numbers that round-trip).
Status saveGeoCameraPath(const GeoCameraPath& path, const std::filesystem::path& file);

// "lat,lon,alt,heading,pitch,fov" (what render --geo-camera takes).
std::string formatGeoCamera(const GeoCamera& camera);

}  // namespace tellus
