#pragma once
// The shaded surface with an optional wireframe overlay, as every renderer draws it: with
// `wireframe` the surface pass is pushed back by a polygon offset and the same triangles are
// drawn again as blended lines (depth GEQUAL, reversed-Z) with `wire`, a program using
// shaders/terrain/wire.frag. Restores the state OffscreenTarget::begin() set. Needs a current
// GL context.
#include <functional>

#include "tellus/core/camera.hpp"
#include "tellus/core/result.hpp"
#include "tellus/gl/program.hpp"

namespace tellus {

// A renderer's two programs over one vertex shader: `fill` with its surface fragment shader,
// `wire` with shaders/terrain/wire.frag for the overlay.
struct FillAndWirePrograms {
  gl::Program fill, wire;
};
Result<FillAndWirePrograms> loadFillAndWirePrograms(const char* vertexShader,
                                                    const char* fillFragmentShader);

// fill(): draws the shaded surface; lines(): draws the same triangles with `wire` in use.
void drawWithWireframeOverlay(bool wireframe, const gl::Program& wire, const ViewSetup& view,
                              const std::function<void()>& fill,
                              const std::function<void()>& lines);

}  // namespace tellus
