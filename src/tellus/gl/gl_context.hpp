#pragma once
// OpenGL 4.5 core contexts. Headless EGL is the default and needs no display: the EGL device
// platform on a vendor driver (NVIDIA), else Mesa's surfaceless platform (llvmpipe here).
// A GLFW window is made on request when a display exists. Creating a context makes it current
// on the calling thread, routes GL debug output to the log (see debug_output.hpp) and checks
// that the version is at least 4.5. All GL objects must be destroyed before their context.
#include <memory>
#include <string>

#include "tellus/core/result.hpp"

struct GLFWwindow;

namespace tellus::gl {

enum class ContextKind { Headless, Window };

struct ContextOptions {
  ContextKind kind = ContextKind::Headless;
  int windowWidth = 1280;  // window kind only, pixels
  int windowHeight = 720;
  bool visibleWindow = true;
  std::string windowTitle = "Tellus";
};

class GlContext {
 public:
  virtual ~GlContext() = default;
  // E.g. "EGL device platform", "EGL surfaceless platform", "GLFW window".
  virtual std::string description() const = 0;
  virtual void swapBuffers() {}
  virtual GLFWwindow* window() const { return nullptr; }
};

// "headless" or "window"; error for anything else.
Result<ContextKind> parseContextKind(std::string_view name);

Result<std::unique_ptr<GlContext>> createGlContext(const ContextOptions& options = {});

// True when the calling thread has a current context, made by EGL or by GLFW (Tellus's or an
// embedder's): GL calls without one would crash.
bool hasCurrentContext();

}  // namespace tellus::gl
