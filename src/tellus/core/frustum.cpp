#include "tellus/core/frustum.hpp"

#include <glm/matrix.hpp>

namespace tellus {

Frustum Frustum::fromMatrix(const glm::dmat4& clipFromWorld) {
  // Rows of the matrix (glm is column-major: m[col][row]).
  const glm::dmat4 t = glm::transpose(clipFromWorld);
  const glm::dvec4 rowX = t[0], rowY = t[1], rowZ = t[2], rowW = t[3];
  Frustum f;
  f.planes_ = {rowW + rowX, rowW - rowX,   // left, right
               rowW + rowY, rowW - rowY,   // bottom, top
               rowZ,        rowW - rowZ};  // z >= 0, z <= w
  return f;
}

bool Frustum::intersects(const Aabb& box) const {
  for (const glm::dvec4& plane : planes_) {
    // The box corner farthest along the plane's normal ("positive vertex").
    const glm::dvec3 positive(plane.x >= 0.0 ? box.max.x : box.min.x,
                              plane.y >= 0.0 ? box.max.y : box.min.y,
                              plane.z >= 0.0 ? box.max.z : box.min.z);
    if (plane.x * positive.x + plane.y * positive.y + plane.z * positive.z + plane.w < 0.0) {
      return false;
    }
  }
  return true;
}

}  // namespace tellus
