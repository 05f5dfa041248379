#include "tellus/gl/glfw_context.hpp"

#include <string>

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

namespace tellus::gl {
namespace {

std::string lastGlfwError() {
  const char* description = nullptr;
  glfwGetError(&description);
  return description ? description : "unknown GLFW error";
}

class GlfwContext final : public GlContext {
 public:
  explicit GlfwContext(GLFWwindow* window) : window_(window) {}
  ~GlfwContext() override {
    glfwDestroyWindow(window_);
    glfwTerminate();
  }
  std::string description() const override { return "GLFW window"; }
  void swapBuffers() override { glfwSwapBuffers(window_); }
  GLFWwindow* window() const override { return window_; }

 private:
  GLFWwindow* window_;
};

}  // namespace

Result<std::unique_ptr<GlContext>> createGlfwContext(const ContextOptions& options) {
  if (!glfwInit()) return makeError("cannot open a window: {}", lastGlfwError());
  glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 4);
  glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 5);
  glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
  glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
  glfwWindowHint(GLFW_OPENGL_DEBUG_CONTEXT, GLFW_TRUE);
  glfwWindowHint(GLFW_VISIBLE, options.visibleWindow ? GLFW_TRUE : GLFW_FALSE);
  GLFWwindow* window = glfwCreateWindow(options.windowWidth, options.windowHeight,
                                        options.windowTitle.c_str(), nullptr, nullptr);
  if (!window) {
    const std::string error = lastGlfwError();
    glfwTerminate();
    return makeError("cannot create an OpenGL 4.5 core window: {}", error);
  }
  glfwMakeContextCurrent(window);
  return std::unique_ptr<GlContext>(std::make_unique<GlfwContext>(window));
}

}  // namespace tellus::gl
