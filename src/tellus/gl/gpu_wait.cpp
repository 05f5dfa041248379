#include "tellus/gl/gpu_wait.hpp"

namespace tellus::gl {
namespace {

thread_local std::uint64_t waits = 0;

}  // namespace

std::uint64_t gpuWaitCount() { return waits; }

void finish() {
  ++waits;
  glFinish();
}

void readBuffer(GLuint buffer, std::size_t offsetBytes, std::size_t bytes, void* out) {
  ++waits;
  glGetNamedBufferSubData(buffer, GLintptr(offsetBytes), GLsizeiptr(bytes), out);
}

void readCompletedBuffer(GLuint buffer, std::size_t offsetBytes, std::size_t bytes, void* out) {
  glGetNamedBufferSubData(buffer, GLintptr(offsetBytes), GLsizeiptr(bytes), out);
}

void readTextureImage(GLuint texture, GLint level, GLenum format, GLenum type, std::size_t bytes,
                      void* out) {
  ++waits;
  glGetTextureImage(texture, level, format, type, GLsizei(bytes), out);
}

void readTextureSubImage(GLuint texture, GLint level, GLint x, GLint y, GLint z, GLsizei width,
                         GLsizei height, GLsizei depth, GLenum format, GLenum type,
                         std::size_t bytes, void* out) {
  ++waits;
  glGetTextureSubImage(texture, level, x, y, z, width, height, depth, format, type, GLsizei(bytes),
                       out);
}

std::uint64_t queryResult(GLuint query) {
  GLint ready = 0;
  glGetQueryObjectiv(query, GL_QUERY_RESULT_AVAILABLE, &ready);
  if (!ready) ++waits;
  GLuint64 value = 0;
  glGetQueryObjectui64v(query, GL_QUERY_RESULT, &value);
  return value;
}

GLenum clientWaitSync(GLsync sync, GLbitfield flags, GLuint64 timeoutNs) {
  if (timeoutNs == 0) return glClientWaitSync(sync, flags, 0);
  const GLenum asked = glClientWaitSync(sync, 0, 0);
  if (asked == GL_ALREADY_SIGNALED || asked == GL_CONDITION_SATISFIED) return asked;
  ++waits;
  return glClientWaitSync(sync, flags, timeoutNs);
}

}  // namespace tellus::gl
