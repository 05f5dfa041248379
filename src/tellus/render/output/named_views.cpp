#include "tellus/render/output/named_views.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <glm/glm.hpp>
#include <glm/gtc/constants.hpp>

namespace tellus {

std::vector<std::string_view> namedViewNames() {
  return {"overview", "oblique", "low"};
}

Camera cameraLookingAt(const glm::dvec3& eye, const glm::dvec3& target, double fovYDeg) {
  const glm::dvec3 d = target - eye;
  Camera camera;
  camera.position = eye;
  camera.fovYDeg = fovYDeg;
  camera.yawDeg = std::atan2(d.x, d.y) * 180.0 / glm::pi<double>();
  camera.pitchDeg = std::atan2(d.z, std::hypot(d.x, d.y)) * 180.0 / glm::pi<double>();
  return camera;
}

Result<Camera> namedView(std::string_view name, const HeightGrid& grid, double aspect) {
  const Aabb bounds = grid.worldBounds();
  const glm::dvec3 size = bounds.size();
  const double extent = std::max(size.x, size.y);
  const glm::dvec3 centre = bounds.centre();
  if (name == "overview") return overviewCamera(bounds, aspect, 40.0, -45.0, 0.0);
  if (name == "oblique") {
    // Above the south-east part, looking at the centre 16 degrees down.
    const glm::dvec3 target(centre.x, centre.y, bounds.min.z + 0.25 * size.z);
    const glm::dvec3 away = glm::normalize(glm::dvec3(size.x, -size.y, 0.0));
    const double distance = 0.6 * extent;
    glm::dvec3 eye = target + away * distance;
    eye.z = target.z + distance * std::tan(16.0 * glm::pi<double>() / 180.0);
    return cameraLookingAt(eye, target, 45.0);
  }
  if (name == "low") {
    // Above the ground a fifth of the way up from the southern edge, looking north.
    const glm::dvec3 ground(centre.x, 0.2 * size.y, 0.0);
    const double above = std::clamp(0.01 * extent, 30.0, 600.0);
    glm::dvec3 eye = ground;
    eye.z = grid.heightAtWorld(ground.x, ground.y) + above;
    const glm::dvec3 target(centre.x, size.y * 0.8, eye.z - 0.04 * size.y);
    return cameraLookingAt(eye, target, 55.0);
  }
  return makeError("unknown view '{}' (expected {})", name, fmt::join(namedViewNames(), ", "));
}

}  // namespace tellus
