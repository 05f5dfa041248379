#include "tellus/core/camera.hpp"

#include "tellus/core/number_fields.hpp"

#include <glm/matrix.hpp>

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <string>

#include <glm/glm.hpp>

#include <glm/gtc/constants.hpp>

namespace tellus {
namespace {

double radians(double degrees) {
  return degrees * glm::pi<double>() / 180.0;
}

}  // namespace

glm::dvec3 Camera::forward() const {
  const double yaw = radians(yawDeg), pitch = radians(pitchDeg);
  return {std::sin(yaw) * std::cos(pitch), std::cos(yaw) * std::cos(pitch), std::sin(pitch)};
}

glm::dvec3 Camera::right() const {
  const double yaw = radians(yawDeg);
  return {std::cos(yaw), -std::sin(yaw), 0.0};
}

glm::dvec3 Camera::up() const {
  return glm::cross(right(), forward());
}

Result<Camera> parseCamera(std::string_view text) {
  static constexpr std::array<const char*, 6> kFields = {"x", "y", "z", "yaw", "pitch", "fov"};
  Result<std::vector<double>> parsed = parseNumberFields(text, kFields, "camera");
  if (!parsed) return parsed.error();
  const std::vector<double>& values = parsed.value();
  Camera camera;
  camera.position = {values[0], values[1], values[2]};
  camera.yawDeg = values[3];
  camera.pitchDeg = values[4];
  camera.fovYDeg = values[5];
  if (Status valid = checkCamera(camera); !valid) {
    return makeError("camera '{}': {}", text, valid.error().message);
  }
  return camera;
}

Status checkCamera(const Camera& camera) {
  static constexpr std::array<const char*, 3> kAxes = {"x", "y", "z"};
  for (int axis = 0; axis < 3; ++axis) {
    const double v = camera.position[axis];
    if (!(std::abs(v) <= kMaxCameraCoordinateM)) {
      return makeError("{} {} m is not within +-{} m", kAxes[std::size_t(axis)], v,
                       kMaxCameraCoordinateM);
    }
  }
  if (!(std::abs(camera.yawDeg) <= kMaxCameraYawDeg)) {
    return makeError("yaw {} is not within +-{} degrees", camera.yawDeg, kMaxCameraYawDeg);
  }
  if (!(camera.pitchDeg >= -90.0 && camera.pitchDeg <= 90.0)) {
    return makeError("pitch {} is outside [-90, 90] degrees", camera.pitchDeg);
  }
  if (!(camera.fovYDeg >= kMinCameraFovDeg && camera.fovYDeg <= kMaxCameraFovDeg)) {
    return makeError("fov {} is outside {} to {} degrees", camera.fovYDeg, kMinCameraFovDeg,
                     kMaxCameraFovDeg);
  }
  return {};
}

ClipRange chooseClipRange(const Camera& camera, const Aabb& bounds) {
  double farthest = 0.0;
  for (const glm::dvec3& corner : bounds.corners()) {
    farthest = std::max(farthest, glm::length(corner - camera.position));
  }
  ClipRange clip;
  clip.nearM = std::max(0.5, 0.5 * bounds.distanceTo(camera.position));
  clip.farM = std::max(clip.nearM * 2.0, farthest * 1.01 + 1.0);
  return clip;
}

glm::dmat4 viewRotation(const Camera& camera) {
  const glm::dvec3 r = camera.right(), u = camera.up(), f = camera.forward();
  glm::dmat4 view(1.0);  // rows: right, up, -forward (glm is column-major: m[col][row])
  for (int i = 0; i < 3; ++i) {
    view[i][0] = r[i];
    view[i][1] = u[i];
    view[i][2] = -f[i];
  }
  return view;
}

glm::dmat4 reversedZProjection(double fovYDeg, double aspect, const ClipRange& clip) {
  const double f = 1.0 / std::tan(radians(fovYDeg) * 0.5);
  const double n = clip.nearM, fa = clip.farM;
  glm::dmat4 p(0.0);
  p[0][0] = f / aspect;
  p[1][1] = f;
  p[2][2] = n / (fa - n);
  p[3][2] = n * fa / (fa - n);
  p[2][3] = -1.0;
  return p;
}

ViewSetup ViewSetup::create(const Camera& camera, const Aabb& bounds, int width, int height) {
  ViewSetup setup;
  setup.camera = camera;
  setup.clip = chooseClipRange(camera, bounds);
  setup.width = width;
  setup.height = height;
  setup.view = viewRotation(camera);
  setup.projection =
      reversedZProjection(camera.fovYDeg, double(width) / double(height), setup.clip);
  setup.viewProjection = setup.projection * setup.view;
  setup.inverseViewProjection = glm::inverse(setup.viewProjection);
  return setup;
}

bool ViewSetup::projectToPixel(const glm::dvec3& world, glm::dvec2& pixel, double* depth) const {
  const glm::dvec4 clipPos = relativeViewProjection() * glm::dvec4(world - camera.position, 1.0);
  if (clipPos.w <= 0.0) return false;
  const glm::dvec3 ndc = glm::dvec3(clipPos) / clipPos.w;
  pixel.x = (ndc.x * 0.5 + 0.5) * width;
  pixel.y = (0.5 - ndc.y * 0.5) * height;
  if (depth) *depth = ndc.z;
  return true;
}

glm::dvec3 ViewSetup::unprojectPixel(const glm::dvec2& pixel, double depth) const {
  const glm::dvec4 ndc{2.0 * pixel.x / width - 1.0, 1.0 - 2.0 * pixel.y / height, depth, 1.0};
  const glm::dvec4 relative = inverseViewProjection * ndc;
  return camera.position + glm::dvec3(relative) / relative.w;
}

Camera overviewCamera(const Aabb& bounds, double aspect, double fovYDeg, double pitchDeg,
                      double yawDeg) {
  Camera camera;
  camera.yawDeg = yawDeg;
  camera.pitchDeg = pitchDeg;
  camera.fovYDeg = fovYDeg;
  const glm::dvec3 centre = bounds.centre();
  const glm::dvec3 back = -camera.forward();
  const glm::dmat4 rotation = viewRotation(camera);
  const double tanY = std::tan(radians(fovYDeg) * 0.5), tanX = tanY * aspect;
  const double margin = 0.9;
  // Does every corner lie inside the central `margin` of the image from distance d?
  const auto fits = [&](double d) {
    const glm::dvec3 eye = centre + back * d;
    for (const glm::dvec3& corner : bounds.corners()) {
      const glm::dvec4 v = rotation * glm::dvec4(corner - eye, 1.0);
      if (-v.z <= 1e-6) return false;
      if (std::abs(v.x) / -v.z > tanX * margin || std::abs(v.y) / -v.z > tanY * margin)
        return false;
    }
    return true;
  };
  double lo = 0.0, hi = std::max(1.0, glm::length(bounds.size()));
  while (!fits(hi)) hi *= 2.0;
  for (int i = 0; i < 60; ++i) {
    const double mid = 0.5 * (lo + hi);
    (fits(mid) ? hi : lo) = mid;
  }
  camera.position = centre + back * hi;
  return camera;
}

}  // namespace tellus
