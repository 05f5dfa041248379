#pragma once
// A view frustum as six planes, for culling boxes. GL-free.
#include <array>

#include <glm/mat4x4.hpp>
#include <glm/vec4.hpp>

#include "tellus/core/aabb.hpp"

namespace tellus {

class Frustum {
 public:
  // The frustum of a clip-space matrix whose depth range is [0, 1] (glClipControl
  // GL_ZERO_TO_ONE, as reversedZProjection produces; reversed or not). Points p with
  // clip = matrix * p inside -w <= x, y <= w and 0 <= z <= w are inside. With a camera-relative
  // matrix (ViewSetup::relativeViewProjection) boxes must be given camera-relative too.
  static Frustum fromMatrix(const glm::dmat4& clipFromWorld);

  // False only when the box lies entirely outside one of the planes (conservative: a box near
  // a frustum corner may be kept although it is outside).
  bool intersects(const Aabb& box) const;

  // Plane i as (normal, d): inside where dot(normal, p) + d >= 0. Normals are not unit length.
  const std::array<glm::dvec4, 6>& planes() const { return planes_; }

 private:
  std::array<glm::dvec4, 6> planes_{};
};

}  // namespace tellus
