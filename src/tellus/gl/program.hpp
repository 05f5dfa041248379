#pragma once
// Linked GLSL program built from shader files of the embedded shader library
// (shaders/ in the source tree). Uniforms are set with DSA (glProgramUniform*), so the program
// need not be bound. Needs a current GL 4.5 context.
#include <cstddef>
#include <initializer_list>
#include <string>
#include <string_view>
#include <unordered_map>
#include <vector>

#include <glm/mat4x4.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include "tellus/core/result.hpp"
#include "tellus/gl/gl_name.hpp"

namespace tellus::gl {

struct ProgramTraits {
  static void destroy(GLuint id) { glDeleteProgram(id); }
};

struct ShaderStage {
  GLenum type;           // GL_VERTEX_SHADER, GL_FRAGMENT_SHADER, ...
  std::string fileName;  // path inside shaders/, e.g. "terrain/reference.vert"
  // Lines ("#define NAME VALUE\n"...) inserted after the #version line: compile-time variants.
  std::string defines = {};
};

class Program {
 public:
  // Compiles and links the stages. The error carries the driver's log, naming the files.
  // feedbackVaryings: outputs of the last vertex-processing stage captured by transform
  // feedback, interleaved into one buffer in this order.
  static Result<Program> fromFiles(const std::vector<ShaderStage>& stages,
                                   const std::vector<std::string>& feedbackVaryings = {});

  void use() const { glUseProgram(id()); }
  GLint location(std::string_view uniform) const;  // -1 when absent (optimised out)

  void set(std::string_view uniform, int value) const;
  void set(std::string_view uniform, float value) const;
  void set(std::string_view uniform, const glm::vec2& value) const;
  void set(std::string_view uniform, const glm::vec3& value) const;
  void set(std::string_view uniform, const glm::vec4& value) const;
  void set(std::string_view uniform, const glm::mat4& value) const;
  void set(std::string_view uniform, const glm::ivec2& value) const;
  void set(std::string_view uniform, const glm::ivec3& value) const;
  void setArray(std::string_view uniform, const int* values, int count) const;
  void setArray(std::string_view uniform, const float* values, int count) const;
  void setArray(std::string_view uniform, const glm::vec2* values, int count) const;
  void setArray(std::string_view uniform, const glm::vec3* values, int count) const;
  void setArray(std::string_view uniform, const glm::vec4* values, int count) const;
  void setArray(std::string_view uniform, const glm::ivec4* values, int count) const;

  GLuint id() const { return name_.id(); }

 private:
  GlName<ProgramTraits> name_;
  // Transparent hash: looking up a string_view allocates nothing once a name is cached.
  struct NameHash {
    using is_transparent = void;
    size_t operator()(std::string_view name) const { return std::hash<std::string_view>{}(name); }
  };
  mutable std::unordered_map<std::string, GLint, NameHash, std::equal_to<>> locations_;
};

// Builds each compute shader file (relative to shaders/) into its program: the first error
// (the file named) stops it.
struct ComputeProgram {
  Program* program;
  const char* file;
};
Status buildComputePrograms(std::initializer_list<ComputeProgram> programs);

// Work groups of `local` invocations that cover `invocations` (the last one partly).
inline GLuint workGroups(std::size_t invocations, std::size_t local) {
  return GLuint((invocations + local - 1) / local);
}

}  // namespace tellus::gl
