#pragma once
// GL vertex array object (DSA). An empty one is what attribute-less draws (vertex pulling from
// gl_VertexID) bind in a core profile. Needs a current GL 4.5 context.
#include "tellus/gl/buffer.hpp"
#include "tellus/gl/gl_name.hpp"

namespace tellus::gl {

struct VertexArrayTraits {
  static void destroy(GLuint id) { glDeleteVertexArrays(1, &id); }
};

class VertexArray {
 public:
  static VertexArray create() {
    GLuint id = 0;
    glCreateVertexArrays(1, &id);
    VertexArray vao;
    vao.name_ = GlName<VertexArrayTraits>(id);
    return vao;
  }
  void setIndexBuffer(const Buffer& indices) { glVertexArrayElementBuffer(id(), indices.id()); }
  // Attribute 0 reads tightly packed vec3 floats from `vertices` (positions).
  void setVec3Positions(const Buffer& vertices) {
    glVertexArrayVertexBuffer(id(), 0, vertices.id(), 0, 3 * sizeof(float));
    glEnableVertexArrayAttrib(id(), 0);
    glVertexArrayAttribFormat(id(), 0, 3, GL_FLOAT, GL_FALSE, 0);
    glVertexArrayAttribBinding(id(), 0, 0);
  }
  void bind() const { glBindVertexArray(id()); }
  GLuint id() const { return name_.id(); }

 private:
  GlName<VertexArrayTraits> name_;
};

}  // namespace tellus::gl
