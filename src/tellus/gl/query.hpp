#pragma once
// GL query object (timer, samples passed, primitives generated). Needs a current GL 4.5 context.
#include <cstdint>

#include "tellus/gl/gl_name.hpp"
#include "tellus/gl/gpu_wait.hpp"

namespace tellus::gl {

struct QueryTraits {
  static void destroy(GLuint id) { glDeleteQueries(1, &id); }
};

class Query {
 public:
  // target: GL_TIME_ELAPSED, GL_SAMPLES_PASSED, GL_PRIMITIVES_GENERATED, GL_TIMESTAMP, ...
  static Query create(GLenum target) {
    GLuint id = 0;
    glCreateQueries(target, 1, &id);
    Query query;
    query.name_ = GlName<QueryTraits>(id);
    query.target_ = target;
    return query;
  }
  void begin() const { glBeginQuery(target_, id()); }
  void end() const { glEndQuery(target_); }
  // True when result() would not stall.
  bool available() const {
    GLint ready = 0;
    glGetQueryObjectiv(id(), GL_QUERY_RESULT_AVAILABLE, &ready);
    return ready != 0;
  }
  // The result (nanoseconds for timers); waits for the GPU if not yet available.
  std::uint64_t result() const { return queryResult(id()); }
  GLuint id() const { return name_.id(); }

 private:
  GlName<QueryTraits> name_;
  GLenum target_ = 0;
};

}  // namespace tellus::gl
