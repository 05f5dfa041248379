#include "tellus/eval/geo_camera_path.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "tellus/core/atomic_output.hpp"
#include "tellus/core/geodesic.hpp"
#include "tellus/core/input_file.hpp"

namespace tellus {
namespace {

constexpr std::size_t kMaxGeoKeyframes = 1'000'000;
constexpr std::size_t kMaxGeoPathBytes = std::size_t(256) << 20;
constexpr double kEarthCircumferenceM = 40'075'017.0;

double wrap180(double degrees) {
  double d = std::fmod(degrees + 180.0, 360.0);
  if (d < 0.0) d += 360.0;
  return d - 180.0;
}

// From a to b the shorter way round, fraction t.
double lerpAngle(double a, double b, double t) { return a + wrap180(b - a) * t; }

double smoothstep(double x) {
  x = std::clamp(x, 0.0, 1.0);
  return x * x * (3.0 - 2.0 * x);
}

Result<double> groundAt(const GroundHeightFn& ground, double lat, double lon) {
  const double h = ground(lat, lon);
  if (!std::isfinite(h)) {
    return makeError("the path passes over ({:.5f}, {:.5f}), where the data has no ground", lat,
                     lon);
  }
  return h;
}

std::vector<GeoCameraKeyframe> descent(double ground, GeoPathTarget target) {
  constexpr int kSteps = 70;
  constexpr double kTopM = 20'000'000.0, kBottomM = 2.0;
  std::vector<GeoCameraKeyframe> keys;
  for (int k = 0; k <= kSteps; ++k) {
    const double s = double(k) / kSteps;
    const double clearance = kBottomM * std::pow(kTopM / kBottomM, 1.0 - s);
    // Straight down above 20 km; levelling to 15 degrees down at 2 m (log of the clearance).
    const double level = smoothstep(1.0 - std::log(clearance / kBottomM) / std::log(1e4));
    GeoCamera c{target.latDeg, target.lonDeg, ground + clearance, 0.0, -90.0 + 75.0 * level, 45.0};
    keys.push_back({s * 60.0, c});
  }
  return keys;
}

std::vector<GeoCameraKeyframe> orbit(GeoPathTarget target) {
  constexpr int kSteps = 72;
  std::vector<GeoCameraKeyframe> keys;
  for (int k = 0; k <= kSteps; ++k) {
    const double along = kEarthCircumferenceM * k / kSteps;
    const GeodesicPoint p = geodesicDirect(target.latDeg, target.lonDeg, 90.0, along);
    keys.push_back({double(k), {p.latDeg, p.lonDeg, 10'000'000.0, p.azimuthDeg, -90.0, 45.0}});
  }
  return keys;
}

Result<std::vector<GeoCameraKeyframe>> lowflight(const GroundHeightFn& ground,
                                                 GeoPathTarget target) {
  constexpr double kHalfM = 150'000.0, kStepM = 5'000.0, kClearanceM = 500.0;
  const GeodesicPoint start = geodesicDirect(target.latDeg, target.lonDeg, 225.0, kHalfM);
  const double heading = wrap180(start.azimuthDeg + 180.0);  // back towards the target
  std::vector<GeoCameraKeyframe> keys;
  const int steps = int(2.0 * kHalfM / kStepM);
  for (int k = 0; k <= steps; ++k) {
    const GeodesicPoint p = geodesicDirect(start.latDeg, start.lonDeg, heading, k * kStepM);
    // The highest ground within a step either side of the track point, every kilometre.
    double highest = -std::numeric_limits<double>::infinity();
    for (double d = -kStepM; d <= kStepM; d += 1000.0) {
      const GeodesicPoint q = geodesicDirect(p.latDeg, p.lonDeg, p.azimuthDeg, d);
      Result<double> g = groundAt(ground, q.latDeg, q.lonDeg);
      if (!g) return g.error();
      highest = std::max(highest, g.value());
    }
    keys.push_back({double(k), {p.latDeg, p.lonDeg, highest + kClearanceM, p.azimuthDeg, -10.0, 50.0}});
  }
  return keys;
}

Result<std::vector<GeoCameraKeyframe>> walk(const GroundHeightFn& ground, GeoPathTarget target) {
  constexpr double kLengthM = 2000.0, kStepM = 10.0, kEyeM = 2.0;
  std::vector<GeoCameraKeyframe> keys;
  for (int k = 0; k <= int(kLengthM / kStepM); ++k) {
    const GeodesicPoint p = geodesicDirect(target.latDeg, target.lonDeg, 90.0, k * kStepM);
    Result<double> g = groundAt(ground, p.latDeg, p.lonDeg);
    if (!g) return g.error();
    keys.push_back({k * kStepM / 1.4, {p.latDeg, p.lonDeg, g.value() + kEyeM, p.azimuthDeg, -5.0, 60.0}});
  }
  return keys;
}

}  // namespace

Result<GeoCameraPath> GeoCameraPath::fromKeyframes(std::vector<GeoCameraKeyframe> keyframes) {
  if (keyframes.size() < 2 || keyframes.size() > kMaxGeoKeyframes) {
    return makeError("a camera path needs 2 to {} keyframes, got {}", kMaxGeoKeyframes,
                     keyframes.size());
  }
  for (std::size_t i = 0; i < keyframes.size(); ++i) {
    const double t = keyframes[i].timeS;
    if (!std::isfinite(t) || std::abs(t) > 1e9 || (i > 0 && !(t > keyframes[i - 1].timeS))) {
      return makeError("keyframe {}: times must be finite and strictly increasing", i);
    }
    if (Status s = checkGeoCamera(keyframes[i].camera); !s) {
      return makeError("keyframe {}: {}", i, s.error().message);
    }
  }
  GeoCameraPath path;
  path.keyframes_ = std::move(keyframes);
  return path;
}

GeoCamera GeoCameraPath::at(double timeS) const {
  const auto& k = keyframes_;
  if (timeS <= k.front().timeS) return k.front().camera;
  if (timeS >= k.back().timeS) return k.back().camera;
  const auto next = std::upper_bound(k.begin(), k.end(), timeS,
                                     [](double t, const GeoCameraKeyframe& key) { return t < key.timeS; });
  const GeoCameraKeyframe& b = *next;
  const GeoCameraKeyframe& a = *(next - 1);
  const double t = (timeS - a.timeS) / (b.timeS - a.timeS);
  GeoCamera c;
  c.latDeg = a.camera.latDeg + (b.camera.latDeg - a.camera.latDeg) * t;
  c.lonDeg = wrap180(lerpAngle(a.camera.lonDeg, b.camera.lonDeg, t));
  c.altitudeM = a.camera.altitudeM > 0.0 && b.camera.altitudeM > 0.0
                    ? a.camera.altitudeM * std::pow(b.camera.altitudeM / a.camera.altitudeM, t)
                    : a.camera.altitudeM + (b.camera.altitudeM - a.camera.altitudeM) * t;
  c.headingDeg = wrap180(lerpAngle(a.camera.headingDeg, b.camera.headingDeg, t));
  c.pitchDeg = a.camera.pitchDeg + (b.camera.pitchDeg - a.camera.pitchDeg) * t;
  c.fovYDeg = a.camera.fovYDeg + (b.camera.fovYDeg - a.camera.fovYDeg) * t;
  return c;
}

std::vector<GeoCamera> GeoCameraPath::sample(int frames) const {
  std::vector<GeoCamera> cameras;
  const double t0 = keyframes_.front().timeS, t1 = keyframes_.back().timeS;
  for (int i = 0; i < frames; ++i) {
    cameras.push_back(at(frames == 1 ? t0 : t0 + (t1 - t0) * i / (frames - 1)));
  }
  return cameras;
}

std::vector<std::string_view> builtInGeoPathNames() { return {"descent", "orbit", "lowflight", "walk"}; }

Result<GeoCameraPath> makeGeoCameraPath(std::string_view nameOrFile, const GroundHeightFn& ground,
                                        GeoPathTarget target) {
  if (Status s = checkGeoCamera({target.latDeg, target.lonDeg, 0.0, 0.0, 0.0, 45.0}); !s) {
    return makeError("--target: {}", s.error().message);
  }
  std::vector<GeoCameraKeyframe> keys;
  if (nameOrFile == "orbit") {
    keys = orbit(target);
  } else if (nameOrFile == "descent") {
    Result<double> g = groundAt(ground, target.latDeg, target.lonDeg);
    if (!g) return g.error();
    keys = descent(g.value(), target);
  } else if (nameOrFile == "lowflight") {
    Result<std::vector<GeoCameraKeyframe>> made = lowflight(ground, target);
    if (!made) return made.error();
    keys = std::move(made.value());
  } else if (nameOrFile == "walk") {
    Result<std::vector<GeoCameraKeyframe>> made = walk(ground, target);
    if (!made) return made.error();
    keys = std::move(made.value());
  } else if (nameOrFile.size() > 5 && nameOrFile.substr(nameOrFile.size() - 5) == ".json") {
    Result<std::string> text = readSmallInputFile(std::filesystem::path(nameOrFile), kMaxGeoPathBytes);
    if (!text) return makeError("cannot read camera path: {}", text.error().message);
    return parseGeoCameraPath(text.value(), std::string(nameOrFile));
  } else {
    return makeError("unknown globe camera path '{}' (descent, orbit, lowflight, walk or a "
                     "keyframe .json file)",
                     nameOrFile);
  }
  return GeoCameraPath::fromKeyframes(std::move(keys));
}

Result<GeoCameraPath> parseGeoCameraPath(std::string_view text, const std::string& name) {
  const nlohmann::json j = nlohmann::json::parse(text, nullptr, /*allow_exceptions=*/false);
  if (j.is_discarded()) return makeError("camera path '{}' is not valid JSON", name);
  if (!j.is_object() || !j.contains("keyframes") || !j.at("keyframes").is_array()) {
    return makeError("camera path '{}' has no \"keyframes\" array", name);
  }
  std::vector<GeoCameraKeyframe> keys;
  try {
    for (const nlohmann::json& k : j.at("keyframes")) {
      GeoCameraKeyframe key;
      key.timeS = k.at("time").get<double>();
      key.camera = {k.at("lat").get<double>(),     k.at("lon").get<double>(),
                    k.at("alt").get<double>(),     k.value("heading", 0.0),
                    k.value("pitch", -90.0),       k.value("fov", 45.0)};
      keys.push_back(key);
    }
  } catch (const nlohmann::json::exception& e) {
    return makeError("camera path '{}': {} (globe keyframes have time, lat, lon, alt and "
                     "optionally heading, pitch, fov)",
                     name, e.what());
  }
  Result<GeoCameraPath> path = GeoCameraPath::fromKeyframes(std::move(keys));
  if (!path) return makeError("camera path '{}': {}", name, path.error().message);
  return path;
}

Status saveGeoCameraPath(const GeoCameraPath& path, const std::filesystem::path& file) {
  nlohmann::json keys = nlohmann::json::array();
  for (const GeoCameraKeyframe& k : path.keyframes()) {
    const GeoCamera& c = k.camera;
    keys.push_back({{"time", k.timeS},         {"lat", c.latDeg},       {"lon", c.lonDeg},
                    {"alt", c.altitudeM},      {"heading", c.headingDeg}, {"pitch", c.pitchDeg},
                    {"fov", c.fovYDeg}});
  }
  return writeTextFileAtomically(file, nlohmann::json{{"keyframes", keys}}.dump(1) + "\n");
}

std::string formatGeoCamera(const GeoCamera& c) {
  return fmt::format("{:.6f},{:.6f},{:.2f},{:.2f},{:.2f},{:.1f}", c.latDeg, c.lonDeg, c.altitudeM,
                     c.headingDeg, c.pitchDeg, c.fovYDeg);
}

}  // namespace tellus
