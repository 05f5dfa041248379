#pragma once
// Cameras computed from the terrain for `--view NAME`: "overview" (the whole terrain, obliquely
// from above, north up), "oblique" (from beyond the south-east corner towards the centre, from
// 16 degrees above), "low" (a few hundred metres above the ground in the southern part of the
// terrain, looking north along it). GL-free.
#include <string_view>
#include <vector>

#include "tellus/core/camera.hpp"
#include "tellus/dem/height_grid.hpp"

namespace tellus {

std::vector<std::string_view> namedViewNames();

// aspect = image width / height. Error for an unknown name.
Result<Camera> namedView(std::string_view name, const HeightGrid& grid, double aspect);

// A camera at `eye` looking at `target` (world metres) with vertical field of view fovYDeg.
Camera cameraLookingAt(const glm::dvec3& eye, const glm::dvec3& target, double fovYDeg);

}  // namespace tellus
