#include "tellus/gl/egl_context.hpp"

#include <cstring>
#include <string>
#include <vector>

#include <epoxy/egl.h>
#include <spdlog/spdlog.h>

namespace tellus::gl {
namespace {

bool hasExtension(const char* list, const char* name) {
  if (!list) return false;
  const size_t length = std::strlen(name);
  for (const char* p = std::strstr(list, name); p; p = std::strstr(p + 1, name)) {
    if ((p == list || p[-1] == ' ') && (p[length] == ' ' || p[length] == '\0')) return true;
  }
  return false;
}

class EglContext final : public GlContext {
 public:
  EglContext(EGLDisplay display, EGLContext context, std::string platform)
      : display_(display), context_(context), platform_(std::move(platform)) {}
  ~EglContext() override {
    eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
    eglDestroyContext(display_, context_);
    eglTerminate(display_);
  }
  std::string description() const override { return "EGL " + platform_ + " platform"; }

 private:
  EGLDisplay display_;
  EGLContext context_;
  std::string platform_;
};

// A display on a hardware EGL device (vendor driver), or EGL_NO_DISPLAY if there is none.
EGLDisplay openHardwareDeviceDisplay(const char* clientExtensions) {
  if (!hasExtension(clientExtensions, "EGL_EXT_device_enumeration") ||
      !hasExtension(clientExtensions, "EGL_EXT_platform_device")) {
    return EGL_NO_DISPLAY;
  }
  EGLint count = 0;
  std::vector<EGLDeviceEXT> devices(16);
  if (!eglQueryDevicesEXT(EGLint(devices.size()), devices.data(), &count)) return EGL_NO_DISPLAY;
  for (EGLint i = 0; i < count; ++i) {
    const char* deviceExtensions = eglQueryDeviceStringEXT(devices[size_t(i)], EGL_EXTENSIONS);
    if (hasExtension(deviceExtensions, "EGL_MESA_device_software")) continue;
    EGLDisplay display =
        eglGetPlatformDisplayEXT(EGL_PLATFORM_DEVICE_EXT, devices[size_t(i)], nullptr);
    EGLint major = 0, minor = 0;
    if (display != EGL_NO_DISPLAY && eglInitialize(display, &major, &minor)) return display;
  }
  return EGL_NO_DISPLAY;
}

}  // namespace

Result<std::unique_ptr<GlContext>> createEglContext() {
  const char* clientExtensions = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
  std::string platform = "device";
  EGLDisplay display = openHardwareDeviceDisplay(clientExtensions);
  if (display == EGL_NO_DISPLAY &&
      hasExtension(clientExtensions, "EGL_MESA_platform_surfaceless")) {
    platform = "surfaceless";
    display = eglGetPlatformDisplayEXT(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
    EGLint major = 0, minor = 0;
    if (display != EGL_NO_DISPLAY && !eglInitialize(display, &major, &minor))
      display = EGL_NO_DISPLAY;
  }
  if (display == EGL_NO_DISPLAY) {
    return makeError(
        "cannot open a headless EGL display (no EGL device and no surfaceless "
        "platform; is Mesa's libegl-mesa0 installed?)");
  }
  if (!eglBindAPI(EGL_OPENGL_API)) {
    eglTerminate(display);
    return makeError("EGL on the {} platform does not offer desktop OpenGL", platform);
  }
  const EGLint configAttribs[] = {EGL_RENDERABLE_TYPE, EGL_OPENGL_BIT, EGL_SURFACE_TYPE,
                                  EGL_DONT_CARE, EGL_NONE};
  EGLConfig config = nullptr;
  EGLint configCount = 0;
  if (!eglChooseConfig(display, configAttribs, &config, 1, &configCount) || configCount == 0) {
    eglTerminate(display);
    return makeError("EGL on the {} platform has no OpenGL config", platform);
  }
  const EGLint contextAttribs[] = {EGL_CONTEXT_MAJOR_VERSION,
                                   4,
                                   EGL_CONTEXT_MINOR_VERSION,
                                   5,
                                   EGL_CONTEXT_OPENGL_PROFILE_MASK,
                                   EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT,
                                   EGL_CONTEXT_OPENGL_DEBUG,
                                   EGL_TRUE,
                                   EGL_NONE};
  EGLContext context = eglCreateContext(display, config, EGL_NO_CONTEXT, contextAttribs);
  if (context == EGL_NO_CONTEXT) {
    eglTerminate(display);
    return makeError(
        "cannot create an OpenGL 4.5 core context on the EGL {} platform (EGL error "
        "0x{:x})",
        platform, eglGetError());
  }
  if (!eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, context)) {
    eglDestroyContext(display, context);
    eglTerminate(display);
    return makeError("cannot make the EGL context current (EGL error 0x{:x})", eglGetError());
  }
  spdlog::debug("EGL {} platform, EGL {}", platform, eglQueryString(display, EGL_VERSION));
  return std::unique_ptr<GlContext>(std::make_unique<EglContext>(display, context, platform));
}

}  // namespace tellus::gl
