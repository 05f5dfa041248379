#include "tellus/eval/camera_path.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include <nlohmann/json.hpp>

#include "tellus/core/atomic_output.hpp"
#include "tellus/core/input_file.hpp"

namespace tellus {
namespace fs = std::filesystem;

namespace {

constexpr double kWalkEyeHeightM = 2.0;
constexpr double kWalkLengthM = 2000.0;
constexpr int kBuiltInKeyframes = 48;  // samples along the built-in paths before smoothing

double catmullRom(double p0, double p1, double p2, double p3, double t) {
  const double t2 = t * t, t3 = t2 * t;
  return 0.5 * (2.0 * p1 + (-p0 + p2) * t + (2.0 * p0 - 5.0 * p1 + 4.0 * p2 - p3) * t2 +
                (-p0 + 3.0 * p1 - 3.0 * p2 + p3) * t3);
}

double wrapDegrees(double d) {
  return d - 360.0 * std::floor((d + 180.0) / 360.0);
}

// Heading (compass degrees) of the horizontal direction (dx, dy).
double headingDeg(double dx, double dy) {
  return std::fmod(std::atan2(dx, dy) * 180.0 / std::numbers::pi + 360.0, 360.0);
}

struct TerrainFrame {
  double width = 0.0, depth = 0.0;  // extent east-west, north-south, metres
  double minZ = 0.0, maxZ = 0.0;
  glm::dvec3 centre{0.0};
};

TerrainFrame terrainFrame(const HeightGrid& terrain) {
  TerrainFrame f;
  f.width = (terrain.width - 1) * terrain.spacingXM;
  f.depth = (terrain.height - 1) * terrain.spacingYM;
  const HeightRange range = terrain.heightRange();
  f.minZ = range.minM;
  f.maxZ = range.maxM;
  f.centre = {0.5 * f.width, 0.5 * f.depth, 0.5 * (f.minZ + f.maxZ)};
  return f;
}

// Fails (rather than aborting) when a terrain's numbers made a camera non-finite.
Result<CameraPath> evenlyTimed(std::vector<Camera> cameras) {
  std::vector<CameraKeyframe> keys;
  for (std::size_t i = 0; i < cameras.size(); ++i) keys.push_back({double(i), cameras[i]});
  Result<CameraPath> path = CameraPath::fromKeyframes(std::move(keys));
  if (!path) return makeError("cannot place a camera path over this terrain: {}", path.error().message);
  return path;
}

Result<CameraPath> orbitPath(const HeightGrid& terrain) {
  const TerrainFrame f = terrainFrame(terrain);
  const double radius = 0.75 * std::max(f.width, f.depth);
  const double altitude = f.maxZ + 0.45 * radius;
  std::vector<Camera> cameras;
  for (int i = 0; i <= kBuiltInKeyframes; ++i) {
    const double a = 2.0 * std::numbers::pi * double(i) / kBuiltInKeyframes;
    const glm::dvec3 eye{f.centre.x - radius * std::sin(a), f.centre.y - radius * std::cos(a),
                         altitude};
    Camera c;
    c.position = eye;
    c.yawDeg = headingDeg(f.centre.x - eye.x, f.centre.y - eye.y);
    c.pitchDeg = -std::atan2(altitude - f.centre.z, radius) * 180.0 / std::numbers::pi;
    c.fovYDeg = 50.0;
    cameras.push_back(c);
  }
  return evenlyTimed(std::move(cameras));
}

// Straight line from `from` to `to` (horizontal), `keyframes` + 1 keyframes, each `clearance`
// above the highest ground within `lookAhead` metres along the line, looking along it `pitch`
// degrees down.
Result<CameraPath> groundFollowingPath(const HeightGrid& terrain, glm::dvec2 from, glm::dvec2 to,
                               int keyframes, double clearance, double lookAheadM,
                               double pitchDeg) {
  const glm::dvec2 dir = glm::normalize(to - from);
  const double length = glm::length(to - from);
  const double step = std::min(terrain.spacingXM, terrain.spacingYM);
  std::vector<Camera> cameras;
  for (int i = 0; i <= keyframes; ++i) {
    const double s = length * double(i) / keyframes;
    double ground = groundUpperBound(terrain, from.x + dir.x * s, from.y + dir.y * s);
    const double increment = std::max(1e-3, std::min(0.25 * step, 0.25 * lookAheadM));
    for (double a = -lookAheadM; a <= lookAheadM; a += increment) {
      const glm::dvec2 p = from + dir * (s + a);
      ground = std::max(ground, groundUpperBound(terrain, p.x, p.y));
    }
    Camera c;
    c.position = {from.x + dir.x * s, from.y + dir.y * s, ground + clearance};
    c.yawDeg = headingDeg(dir.x, dir.y);
    c.pitchDeg = pitchDeg;
    c.fovYDeg = 60.0;
    cameras.push_back(c);
  }
  return evenlyTimed(std::move(cameras));
}

Result<CameraPath> flyoverPath(const HeightGrid& terrain) {
  const TerrainFrame f = terrainFrame(terrain);
  const double extent = std::max(f.width, f.depth);
  // Clear the ground within 3% of the extent by 4% of the relief plus 1.5% of the extent.
  const double clearance = 0.04 * (f.maxZ - f.minZ) + 0.015 * extent;
  // Keyframes 2.6% of the extent apart, each clearing +-3%: segments clear the ground between.
  return groundFollowingPath(terrain, {0.05 * f.width, 0.05 * f.depth},
                             {0.95 * f.width, 0.95 * f.depth}, kBuiltInKeyframes, clearance,
                             0.03 * extent, -12.0);
}

// The walk: up to 2 km (a fifth of the width at most) through the centre, keyframes every
// quarter sample spacing, each clearing the ground up to the neighbouring keyframes by the eye
// height, so the smoothed path stays above the mesh between them.
Result<CameraPath> walkPath(const HeightGrid& terrain) {
  const TerrainFrame f = terrainFrame(terrain);
  const double half = std::min(0.1 * f.width, kWalkLengthM / 2);
  const double step = std::min(terrain.spacingXM, terrain.spacingYM);
  const int keyframes = int(std::clamp(2.0 * half / (0.25 * step), 2.0, 4000.0));
  const double keySpacing = 2.0 * half / keyframes;
  return groundFollowingPath(terrain, {f.centre.x - half, f.centre.y},
                             {f.centre.x + half, f.centre.y}, keyframes, kWalkEyeHeightM,
                             1.5 * keySpacing, -4.0);
}

// Seed 004's rotation test: keyframes at every degree, so sample(360) gives yaw 0, 1, ... 359.
Result<CameraPath> rotatePath(const HeightGrid& terrain) {
  const TerrainFrame f = terrainFrame(terrain);
  const double radius = 0.01 * std::max(f.width, f.depth);
  double ground = groundUpperBound(terrain, f.centre.x, f.centre.y);
  for (int i = 0; i < 16; ++i) {  // the highest ground on a circle around the position
    const double a = 2.0 * std::numbers::pi * double(i) / 16.0;
    ground = std::max(ground, groundUpperBound(terrain, f.centre.x + radius * std::cos(a),
                                               f.centre.y + radius * std::sin(a)));
  }
  std::vector<Camera> cameras;
  for (int degree = 0; degree < 360; ++degree) {
    Camera c;
    c.position = {f.centre.x, f.centre.y, ground + 0.02 * (f.maxZ - f.minZ) + 20.0};
    c.yawDeg = double(degree);
    c.pitchDeg = -8.0;
    c.fovYDeg = 60.0;
    cameras.push_back(c);
  }
  return evenlyTimed(std::move(cameras));
}

}  // namespace

double groundUpperBound(const HeightGrid& terrain, double x, double y) {
  // A NaN position (an absurd spacing upstream) must not become int(NaN): it reads sample 0.
  const auto clampFinite = [](double v, double hi) { return std::isfinite(v) ? std::clamp(v, 0.0, hi) : 0.0; };
  const double col = clampFinite(x / terrain.spacingXM, double(terrain.width - 1));
  const double row = clampFinite(double(terrain.height - 1) - y / terrain.spacingYM, double(terrain.height - 1));
  const int c0 = std::min(int(col), terrain.width - 2), r0 = std::min(int(row), terrain.height - 2);
  const double fx = col - c0, fy = row - r0;
  const double h00 = terrain.at(c0, r0), h10 = terrain.at(c0 + 1, r0);
  const double h01 = terrain.at(c0, r0 + 1), h11 = terrain.at(c0 + 1, r0 + 1);
  const double bilinear = (h00 * (1 - fx) + h10 * fx) * (1 - fy) + (h01 * (1 - fx) + h11 * fx) * fy;
  // Diagonal h00-h11: triangles (00, 10, 11) above it and (00, 11, 01) below.
  const double mainDiagonal = fx >= fy ? h00 + (h10 - h00) * fx + (h11 - h10) * fy
                                       : h00 + (h01 - h00) * fy + (h11 - h01) * fx;
  // Diagonal h10-h01.
  const double otherDiagonal = fx + fy <= 1.0
                                   ? h00 + (h10 - h00) * fx + (h01 - h00) * fy
                                   : h11 + (h01 - h11) * (1 - fx) + (h10 - h11) * (1 - fy);
  return std::max({bilinear, mainDiagonal, otherDiagonal});
}

Result<CameraPath> CameraPath::fromKeyframes(std::vector<CameraKeyframe> keyframes) {
  if (keyframes.size() < 2) return makeError("a camera path needs at least two keyframes");
  if (keyframes.size() > kMaxKeyframes) {
    return makeError("a camera path holds at most {} keyframes, got {}", kMaxKeyframes,
                     keyframes.size());
  }
  for (std::size_t i = 0; i < keyframes.size(); ++i) {
    const CameraKeyframe& k = keyframes[i];
    if (!(std::abs(k.timeS) <= kMaxKeyframeTimeS)) {
      return makeError("keyframe {}: time {} s is not within +-{} s", i, k.timeS,
                       kMaxKeyframeTimeS);
    }
    if (Status valid = checkCamera(k.camera); !valid) {
      return makeError("keyframe {}: {}", i, valid.error().message);
    }
    if (i > 0 && !(k.timeS > keyframes[i - 1].timeS)) {
      return makeError("keyframe {}: time {} s does not increase (previous {} s)", i, k.timeS,
                       keyframes[i - 1].timeS);
    }
  }
  // Unwrap yaw so that consecutive keyframes turn the shorter way round.
  for (std::size_t i = 1; i < keyframes.size(); ++i) {
    const double previous = keyframes[i - 1].camera.yawDeg;
    keyframes[i].camera.yawDeg = previous + wrapDegrees(keyframes[i].camera.yawDeg - previous);
  }
  CameraPath path;
  path.keyframes_ = std::move(keyframes);
  return path;
}

Camera CameraPath::at(double timeS) const {
  const std::vector<CameraKeyframe>& k = keyframes_;
  const double t = std::clamp(timeS, k.front().timeS, k.back().timeS);
  std::size_t i = std::size_t(
      std::upper_bound(k.begin(), k.end(), t,
                       [](double v, const CameraKeyframe& key) { return v < key.timeS; }) -
      k.begin());
  i = std::clamp<std::size_t>(i, 1, k.size() - 1) - 1;  // segment [i, i + 1]
  const Camera& c0 = k[i == 0 ? 0 : i - 1].camera;
  const Camera& c1 = k[i].camera;
  const Camera& c2 = k[i + 1].camera;
  const Camera& c3 = k[std::min(i + 2, k.size() - 1)].camera;
  const double u = (t - k[i].timeS) / (k[i + 1].timeS - k[i].timeS);
  Camera c;
  for (int axis = 0; axis < 3; ++axis) {
    c.position[axis] =
        catmullRom(c0.position[axis], c1.position[axis], c2.position[axis], c3.position[axis], u);
  }
  c.yawDeg =
      std::fmod(catmullRom(c0.yawDeg, c1.yawDeg, c2.yawDeg, c3.yawDeg, u) + 360.0 * 1000.0, 360.0);
  c.pitchDeg =
      std::clamp(catmullRom(c0.pitchDeg, c1.pitchDeg, c2.pitchDeg, c3.pitchDeg, u), -90.0, 90.0);
  c.fovYDeg = std::clamp(catmullRom(c0.fovYDeg, c1.fovYDeg, c2.fovYDeg, c3.fovYDeg, u), 1.0, 170.0);
  return c;
}

std::vector<Camera> CameraPath::sample(int frames) const {
  std::vector<Camera> cameras;
  const int n = std::max(frames, 1);
  for (int i = 0; i < n; ++i) {
    const double t = n == 1 ? 0.0 : double(i) / double(n - 1);
    cameras.push_back(at(keyframes_.front().timeS + t * durationS()));
  }
  return cameras;
}

std::vector<std::string_view> builtInPathNames() {
  return {"orbit", "flyover", "walk", "rotate"};
}

Result<CameraPath> makeCameraPath(std::string_view nameOrFile, const HeightGrid& terrain) {
  if (nameOrFile == "orbit") return orbitPath(terrain);
  if (nameOrFile == "flyover") return flyoverPath(terrain);
  if (nameOrFile == "walk") return walkPath(terrain);
  if (nameOrFile == "rotate") return rotatePath(terrain);
  if (fs::path(nameOrFile).extension() == ".json") return loadCameraPath(fs::path(nameOrFile));
  return makeError(
      "unknown camera path '{}' (choose orbit, flyover, walk, rotate or a keyframe .json file)",
      nameOrFile);
}

Result<CameraPath> loadCameraPath(const fs::path& file) {
  Result<std::string> text = readSmallInputFile(file, kMaxCameraPathBytes);
  if (!text) return makeError("cannot read camera path: {}", text.error().message);
  return parseCameraPath(text.value(), file.string());
}

Result<CameraPath> parseCameraPath(std::string_view text, const std::string& name) {
  const nlohmann::json j = nlohmann::json::parse(text, nullptr, /*allow_exceptions=*/false);
  if (j.is_discarded()) return makeError("camera path '{}' is not valid JSON", name);
  if (!j.is_object() || !j.contains("keyframes") || !j.at("keyframes").is_array()) {
    return makeError("camera path '{}' has no \"keyframes\" array", name);
  }
  std::vector<CameraKeyframe> keys;
  try {
    for (const nlohmann::json& k : j.at("keyframes")) {
      CameraKeyframe key;
      key.timeS = k.at("time").get<double>();
      const auto p = k.at("position").get<std::array<double, 3>>();
      key.camera.position = {p[0], p[1], p[2]};
      key.camera.yawDeg = k.at("yaw").get<double>();
      key.camera.pitchDeg = k.at("pitch").get<double>();
      key.camera.fovYDeg = k.value("fov", 45.0);
      keys.push_back(key);
    }
  } catch (const nlohmann::json::exception& e) {
    return makeError("camera path '{}': {}", name, e.what());
  }
  Result<CameraPath> path = CameraPath::fromKeyframes(std::move(keys));
  if (!path) return makeError("camera path '{}': {}", name, path.error().message);
  return path;
}

Status saveCameraPath(const CameraPath& path, const fs::path& file) {
  nlohmann::json keys = nlohmann::json::array();
  for (const CameraKeyframe& k : path.keyframes()) {
    const Camera& c = k.camera;
    keys.push_back({{"time", k.timeS},
                    {"position", {c.position.x, c.position.y, c.position.z}},
                    {"yaw", wrapDegrees(c.yawDeg)},
                    {"pitch", c.pitchDeg},
                    {"fov", c.fovYDeg}});
  }
  const std::string text = nlohmann::json{{"keyframes", keys}}.dump(1) + "\n";
  return writeTextFileAtomically(file, text);
}

}  // namespace tellus
