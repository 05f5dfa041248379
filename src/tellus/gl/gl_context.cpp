#include "tellus/gl/gl_context.hpp"

#include <epoxy/egl.h>
#include <epoxy/gl.h>
#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

#include <spdlog/spdlog.h>

#include "tellus/gl/debug_output.hpp"
#include "tellus/gl/driver_workarounds.hpp"
#include "tellus/gl/egl_context.hpp"
#include "tellus/gl/glfw_context.hpp"

namespace tellus::gl {

Result<ContextKind> parseContextKind(std::string_view name) {
  if (name == "headless") return ContextKind::Headless;
  if (name == "window") return ContextKind::Window;
  return makeError("unknown context kind '{}' (expected headless or window)", name);
}

Result<std::unique_ptr<GlContext>> createGlContext(const ContextOptions& options) {
  // Before the driver loads: it reads its environment once.
  static const bool logged = [] {
    const DriverWorkaround w = applyDriverWorkarounds();
    if (w.variable) spdlog::debug("{}={}: {}", w.variable, w.value, w.reason);
    return true;
  }();
  (void)logged;
  Result<std::unique_ptr<GlContext>> context =
      options.kind == ContextKind::Headless ? createEglContext() : createGlfwContext(options);
  if (!context) return context;
  const int version = epoxy_gl_version();
  if (version < 45) {
    return makeError("{} gives OpenGL {}.{}; Tellus needs 4.5 core", context.value()->description(),
                     version / 10, version % 10);
  }
  installDebugOutput();
  return context;
}

bool hasCurrentContext() {
  if (eglGetCurrentContext() != EGL_NO_CONTEXT) return true;
  // GLFW answers null (and reports GLFW_NOT_INITIALIZED) when nobody initialised it.
  return glfwGetCurrentContext() != nullptr;
}

}  // namespace tellus::gl
