#pragma once
// GlName<Traits>: the move-only ownership of one OpenGL object name, shared by every RAII
// wrapper in this folder. Traits::destroy(GLuint) deletes the object. Needs a current context
// when the owned name is destroyed.
#include <utility>

#include <epoxy/gl.h>

namespace tellus::gl {

template <typename Traits>
class GlName {
 public:
  GlName() = default;
  explicit GlName(GLuint id) : id_(id) {}
  ~GlName() { reset(); }
  GlName(const GlName&) = delete;
  GlName& operator=(const GlName&) = delete;
  GlName(GlName&& other) noexcept : id_(std::exchange(other.id_, 0)) {}
  GlName& operator=(GlName&& other) noexcept {
    if (this != &other) {
      reset();
      id_ = std::exchange(other.id_, 0);
    }
    return *this;
  }

  GLuint id() const { return id_; }
  explicit operator bool() const { return id_ != 0; }
  // Gives up ownership without deleting.
  GLuint release() { return std::exchange(id_, 0); }
  void reset() {
    if (id_ != 0) Traits::destroy(std::exchange(id_, 0));
  }

 private:
  GLuint id_ = 0;
};

}  // namespace tellus::gl
