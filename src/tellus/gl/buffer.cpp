#include "tellus/gl/buffer.hpp"

#include "tellus/gl/gpu_wait.hpp"

namespace tellus::gl {

Buffer::Buffer(std::size_t bytes, const void* data, GLbitfield flags) : size_(bytes) {
  GLuint id = 0;
  glCreateBuffers(1, &id);
  name_ = GlName<BufferTraits>(id);
  glNamedBufferStorage(id, GLsizeiptr(bytes), data, flags);
}

void Buffer::upload(std::size_t offsetBytes, std::size_t bytes, const void* data) {
  glNamedBufferSubData(id(), GLintptr(offsetBytes), GLsizeiptr(bytes), data);
}

void Buffer::download(std::size_t offsetBytes, std::size_t bytes, void* out) const {
  readBuffer(id(), offsetBytes, bytes, out);
}

}  // namespace tellus::gl
