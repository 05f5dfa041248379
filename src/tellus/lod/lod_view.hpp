#pragma once
// The view a level-of-detail selection on the CPU refines for: the camera in world metres, its
// camera-relative frustum, and the scale that turns a world-space error at a distance into
// pixels (error_px = error_m * exaggeration * pixelsPerRadian / distance_m).
#include <glm/mat3x3.hpp>
#include <glm/vec3.hpp>

#include "tellus/core/camera.hpp"
#include "tellus/core/frustum.hpp"

namespace tellus {

struct LodView {
  glm::dvec3 cameraM{0.0};  // world metres
  Frustum frustum;          // camera-relative (ViewSetup::relativeViewProjection)
  double pixelsPerRadian = 1.0;
  double nearM = 1.0;
  float exaggeration = 1.0f;
  glm::dmat3 rotation{1.0};  // world -> camera axes (ViewSetup::view)
  double aspect = 1.0;

  static LodView fromSetup(const ViewSetup& view, float exaggeration);
};

}  // namespace tellus
