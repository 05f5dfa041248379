#include "tellus/gl/debug_output.hpp"

#include <atomic>
#include <string_view>

#include <epoxy/gl.h>
#include <spdlog/spdlog.h>

namespace tellus::gl {
namespace {

std::atomic<std::uint64_t> gErrorCount{0};

void GLAPIENTRY onDebugMessage(GLenum source, GLenum type, GLuint id, GLenum severity,
                               GLsizei length, const GLchar* message, const void*) {
  (void)source;
  const std::string_view text(
      message, length > 0 ? size_t(length) : std::char_traits<char>::length(message));
  if (type == GL_DEBUG_TYPE_ERROR) {
    ++gErrorCount;
    spdlog::error("GL error {}: {}", id, text);
  } else if (severity == GL_DEBUG_SEVERITY_HIGH || severity == GL_DEBUG_SEVERITY_MEDIUM) {
    spdlog::warn("GL: {}", text);
  } else {
    spdlog::debug("GL: {}", text);
  }
}

}  // namespace

void installDebugOutput() {
  if (!epoxy_has_gl_extension("GL_KHR_debug") && epoxy_gl_version() < 43) return;
  glEnable(GL_DEBUG_OUTPUT);
  glEnable(GL_DEBUG_OUTPUT_SYNCHRONOUS);
  glDebugMessageCallback(onDebugMessage, nullptr);
  glDebugMessageControl(GL_DONT_CARE, GL_DONT_CARE, GL_DONT_CARE, 0, nullptr, GL_TRUE);
}

std::uint64_t glErrorCount() {
  return gErrorCount.load();
}

int checkGlErrors(const char* where) {
  int count = 0;
  for (GLenum code = glGetError(); code != GL_NO_ERROR; code = glGetError()) {
    ++count;
    ++gErrorCount;
    spdlog::error("GL error 0x{:x} at {}", code, where);
  }
  return count;
}

}  // namespace tellus::gl
