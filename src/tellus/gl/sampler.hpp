#pragma once
// GL sampler object (DSA). Needs a current GL 4.5 context.
#include "tellus/gl/gl_name.hpp"

namespace tellus::gl {

struct SamplerTraits {
  static void destroy(GLuint id) { glDeleteSamplers(1, &id); }
};

class Sampler {
 public:
  // Creates a sampler with the given filters and wrap mode on all axes.
  static Sampler create(GLenum minFilter, GLenum magFilter, GLenum wrap);
  void bindUnit(GLuint unit) const { glBindSampler(unit, id()); }
  GLuint id() const { return name_.id(); }

 private:
  GlName<SamplerTraits> name_;
};

inline Sampler Sampler::create(GLenum minFilter, GLenum magFilter, GLenum wrap) {
  GLuint id = 0;
  glCreateSamplers(1, &id);
  Sampler sampler;
  sampler.name_ = GlName<SamplerTraits>(id);
  glSamplerParameteri(id, GL_TEXTURE_MIN_FILTER, GLint(minFilter));
  glSamplerParameteri(id, GL_TEXTURE_MAG_FILTER, GLint(magFilter));
  glSamplerParameteri(id, GL_TEXTURE_WRAP_S, GLint(wrap));
  glSamplerParameteri(id, GL_TEXTURE_WRAP_T, GLint(wrap));
  glSamplerParameteri(id, GL_TEXTURE_WRAP_R, GLint(wrap));
  return sampler;
}

}  // namespace tellus::gl
