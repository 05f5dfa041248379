#pragma once
// OpenGL 4.5 core context in a GLFW window (needs a display, e.g. X11 or Xvfb).
#include <memory>

#include "tellus/gl/gl_context.hpp"

namespace tellus::gl {

Result<std::unique_ptr<GlContext>> createGlfwContext(const ContextOptions& options);

}  // namespace tellus::gl
