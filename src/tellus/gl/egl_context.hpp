#pragma once
// Headless OpenGL 4.5 core context through EGL, without any surface (see gl_context.hpp).
#include <memory>

#include "tellus/gl/gl_context.hpp"

namespace tellus::gl {

Result<std::unique_ptr<GlContext>> createEglContext();

}  // namespace tellus::gl
