#pragma once
// GL transform feedback object (DSA): remembers the buffer it captures into and how many
// primitives the last capture wrote, so glDrawTransformFeedback can draw them without the
// CPU reading the count back. Needs a current GL 4.5 context.
#include "tellus/gl/buffer.hpp"
#include "tellus/gl/gl_name.hpp"

namespace tellus::gl {

struct TransformFeedbackTraits {
  static void destroy(GLuint id) { glDeleteTransformFeedbacks(1, &id); }
};

class TransformFeedback {
 public:
  static TransformFeedback create() {
    GLuint id = 0;
    glCreateTransformFeedbacks(1, &id);
    TransformFeedback feedback;
    feedback.name_ = GlName<TransformFeedbackTraits>(id);
    return feedback;
  }
  // Captures into `buffer` (binding 0, the whole buffer).
  void captureInto(const Buffer& buffer) const {
    glTransformFeedbackBufferBase(id(), 0, buffer.id());
  }
  void bind() const { glBindTransformFeedback(GL_TRANSFORM_FEEDBACK, id()); }
  GLuint id() const { return name_.id(); }

 private:
  GlName<TransformFeedbackTraits> name_;
};

}  // namespace tellus::gl
