#pragma once
// GL framebuffer object (DSA). Needs a current GL 4.5 context.
#include "tellus/core/result.hpp"
#include "tellus/gl/gl_name.hpp"
#include "tellus/gl/texture.hpp"

namespace tellus::gl {

struct FramebufferTraits {
  static void destroy(GLuint id) { glDeleteFramebuffers(1, &id); }
};

class Framebuffer {
 public:
  static Framebuffer create() {
    GLuint id = 0;
    glCreateFramebuffers(1, &id);
    Framebuffer fbo;
    fbo.name_ = GlName<FramebufferTraits>(id);
    return fbo;
  }
  // attachment: GL_COLOR_ATTACHMENT0, GL_DEPTH_ATTACHMENT, ...
  void attach(GLenum attachment, const Texture& texture, int level = 0) {
    glNamedFramebufferTexture(id(), attachment, texture.id(), level);
  }
  // Error naming the incomplete status when the framebuffer cannot be rendered to.
  Status checkComplete() const;
  void bind() const { glBindFramebuffer(GL_FRAMEBUFFER, id()); }
  GLuint id() const { return name_.id(); }

 private:
  GlName<FramebufferTraits> name_;
};

inline Status Framebuffer::checkComplete() const {
  const GLenum status = glCheckNamedFramebufferStatus(id(), GL_FRAMEBUFFER);
  if (status != GL_FRAMEBUFFER_COMPLETE) return makeError("framebuffer incomplete: 0x{:x}", status);
  return {};
}

}  // namespace tellus::gl
