#pragma once
// Immutable-storage GL buffer object (DSA). Needs a current GL 4.5 context.
#include <cstddef>
#include <span>

#include "tellus/gl/gl_name.hpp"

namespace tellus::gl {

struct BufferTraits {
  static void destroy(GLuint id) { glDeleteBuffers(1, &id); }
};

class Buffer {
 public:
  Buffer() = default;
  // Allocates `bytes` of storage, initialised from `data` when not null. flags: glBufferStorage's.
  Buffer(std::size_t bytes, const void* data, GLbitfield flags = 0);
  template <typename T>
  explicit Buffer(std::span<const T> data, GLbitfield flags = 0)
      : Buffer(data.size_bytes(), data.data(), flags) {}

  void upload(std::size_t offsetBytes, std::size_t bytes, const void* data);
  // Reads back; the calling thread waits for the GPU (counted: gpu_wait.hpp).
  void download(std::size_t offsetBytes, std::size_t bytes, void* out) const;
  void bindBase(GLenum target, GLuint index) const { glBindBufferBase(target, index, id()); }

  GLuint id() const { return name_.id(); }
  std::size_t size() const { return size_; }

 private:
  GlName<BufferTraits> name_;
  std::size_t size_ = 0;
};

}  // namespace tellus::gl
