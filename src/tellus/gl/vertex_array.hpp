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
  // Binding `binding` reads one element of `stride` bytes a instance from `perInstance`
  // (divisor 1: a draw's base instance picks its element).
  void setInstanceBuffer(GLuint binding, const Buffer& perInstance, GLsizei stride) {
    glVertexArrayVertexBuffer(id(), binding, perInstance.id(), 0, stride);
    glVertexArrayBindingDivisor(id(), binding, 1);
  }
  // Attribute `attribute` reads `components` floats (or unsigned ints, for integer shader
  // inputs) at `offset` bytes into binding `binding`'s elements.
  void setFloatAttribute(GLuint attribute, GLuint binding, int components, GLuint offset) {
    glEnableVertexArrayAttrib(id(), attribute);
    glVertexArrayAttribFormat(id(), attribute, components, GL_FLOAT, GL_FALSE, offset);
    glVertexArrayAttribBinding(id(), attribute, binding);
  }
  void setUintAttribute(GLuint attribute, GLuint binding, int components, GLuint offset) {
    glEnableVertexArrayAttrib(id(), attribute);
    glVertexArrayAttribIFormat(id(), attribute, components, GL_UNSIGNED_INT, offset);
    glVertexArrayAttribBinding(id(), attribute, binding);
  }
  void bind() const { glBindVertexArray(id()); }
  GLuint id() const { return name_.id(); }

 private:
  GlName<VertexArrayTraits> name_;
};

}  // namespace tellus::gl
