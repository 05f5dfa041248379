#pragma once
// Many axis-aligned boxes tested against a frustum at once. The boxes are kept as float centres
// and half extents in a structure of arrays, so the test is a loop the compiler vectorises: a
// few nanoseconds a box, where Frustum::intersects (double precision, a branch a plane) takes
// tens. The answer is Frustum::intersects's for every box, except that float rounding may keep
// a box that lies outside by about a millionth of the farthest distance in the set (never the
// other way: every box is widened by that much).
// GL-free.
#include <cstdint>
#include <span>
#include <vector>

#include <glm/vec3.hpp>

#include "tellus/core/aabb.hpp"
#include "tellus/core/frustum.hpp"

namespace tellus {

class BoxCullSet {
 public:
  BoxCullSet() = default;
  // `boxes` in world metres, vertical unexaggerated.
  explicit BoxCullSet(std::span<const Aabb> boxes);
  // The boxes of `items` (boxOf(item) gives one's Aabb), in their order.
  template <class Items, class BoxOf>
  static BoxCullSet of(const Items& items, BoxOf boxOf) {
    std::vector<Aabb> boxes;
    boxes.reserve(items.size());
    for (const auto& item : items) boxes.push_back(boxOf(item));
    return BoxCullSet(boxes);
  }

  std::size_t size() const { return centreX_.size(); }

  // ORs `bit` into flags[i] (flags is resized to size() first, new entries 0) for every box i
  // that Frustum::intersects keeps: `frustum` is camera-relative (ViewSetup's relative matrix),
  // the camera at `camera` (world metres), boxes' heights and vertical extents scaled by
  // `exaggeration`.
  void markInside(const Frustum& frustum, const glm::dvec3& camera, double exaggeration, std::uint8_t bit,
                  std::vector<std::uint8_t>& flags) const;

 private:
  glm::dvec3 origin_{0.0};  // the boxes' common origin (their bounds' centre), metres
  double radius_ = 0.0;     // of the sphere around the origin that holds every box, metres
  // Per box, relative to origin_, metres.
  std::vector<float> centreX_, centreY_, centreZ_, halfX_, halfY_, halfZ_;
};

}  // namespace tellus
