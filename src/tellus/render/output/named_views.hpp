#pragma once
// Cameras computed from the terrain for `--view NAME`:
//   "overview": the whole terrain obliquely from above, north up;
//   "oblique":  from above the south-east part of the terrain (0.6 extents from the centre),
//               looking at the centre 16 degrees down;
//   "low":      a little above the ground a fifth of the way up from the southern edge, looking
//               north along the terrain.
// GL-free.
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
