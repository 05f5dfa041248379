#pragma once
// The shaded surface with an optional wireframe overlay, as every renderer draws it: with
// `wireframe` the surface pass is pushed back by a polygon offset and the same triangles are
// drawn again as blended lines (depth GEQUAL, reversed-Z) with `wire`, a program using
// shaders/terrain/wire.frag. Restores the state OffscreenTarget::begin() set. Needs a current
// GL context.
#include <functional>

#include "tellus/core/camera.hpp"
#include "tellus/gl/program.hpp"

namespace tellus {

// fill(): draws the shaded surface; lines(): draws the same triangles with `wire` in use.
void drawWithWireframeOverlay(bool wireframe, const gl::Program& wire, const ViewSetup& view,
                              const std::function<void()>& fill,
                              const std::function<void()>& lines);

}  // namespace tellus
