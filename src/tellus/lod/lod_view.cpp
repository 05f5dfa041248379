#include "tellus/lod/lod_view.hpp"

#include <algorithm>
#include <cmath>

#include <glm/trigonometric.hpp>

namespace tellus {

LodView LodView::fromSetup(const ViewSetup& view, float exaggeration) {
  LodView out;
  out.cameraM = view.camera.position;
  out.frustum = Frustum::fromMatrix(view.relativeViewProjection());
  const double halfFov = glm::radians(view.camera.fovYDeg) * 0.5;
  out.pixelsPerRadian = double(view.height) / (2.0 * std::tan(halfFov));
  out.nearM = view.clip.nearM;
  out.exaggeration = exaggeration;
  out.rotation = glm::dmat3(view.view);
  out.aspect = double(view.width) / double(std::max(1, view.height));
  return out;
}

}  // namespace tellus
