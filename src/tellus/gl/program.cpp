#include "tellus/gl/program.hpp"

#include <glm/gtc/type_ptr.hpp>

#include "tellus/gl/shader_library.hpp"

namespace tellus::gl {
namespace {

std::string shaderLog(GLuint shader) {
  GLint length = 0;
  glGetShaderiv(shader, GL_INFO_LOG_LENGTH, &length);
  std::string log(size_t(std::max(length, 1)), '\0');
  glGetShaderInfoLog(shader, length, nullptr, log.data());
  return log.c_str();
}

std::string programLog(GLuint program) {
  GLint length = 0;
  glGetProgramiv(program, GL_INFO_LOG_LENGTH, &length);
  std::string log(size_t(std::max(length, 1)), '\0');
  glGetProgramInfoLog(program, length, nullptr, log.data());
  return log.c_str();
}

std::string fileLegend(const std::vector<std::string>& files) {
  std::string legend;
  for (size_t i = 0; i < files.size(); ++i) legend += fmt::format(" [{} = {}]", i, files[i]);
  return legend;
}

}  // namespace

Result<Program> Program::fromFiles(const std::vector<ShaderStage>& stages,
                                   const std::vector<std::string>& feedbackVaryings) {
  Program program;
  program.name_ = GlName<ProgramTraits>(glCreateProgram());
  std::vector<GLuint> shaders;
  const auto deleteShaders = [&] {
    for (GLuint s : shaders) glDeleteShader(s);
  };
  std::string names;
  for (const ShaderStage& stage : stages) {
    names += (names.empty() ? "" : ", ") + stage.fileName;
    Result<ExpandedShader> source = loadShader(stage.fileName);
    if (!source) {
      deleteShaders();
      return source.error();
    }
    const GLuint shader = glCreateShader(stage.type);
    shaders.push_back(shader);
    if (!stage.defines.empty()) {
      // After the #version line, then back to the file's own line numbers.
      const std::size_t versionEnd = source->source.find('\n');
      if (versionEnd != std::string::npos) {
        source->source.insert(versionEnd + 1, stage.defines + "\n#line 2 0\n");
      }
    }
    const char* text = source->source.c_str();
    glShaderSource(shader, 1, &text, nullptr);
    glCompileShader(shader);
    GLint compiled = 0;
    glGetShaderiv(shader, GL_COMPILE_STATUS, &compiled);
    if (!compiled) {
      const std::string log = shaderLog(shader);
      deleteShaders();
      return makeError("cannot compile shader '{}'{}: {}", stage.fileName,
                       fileLegend(source->files), log);
    }
    glAttachShader(program.id(), shader);
  }
  if (!feedbackVaryings.empty()) {
    std::vector<const char*> varyingNames;
    for (const std::string& varying : feedbackVaryings) varyingNames.push_back(varying.c_str());
    glTransformFeedbackVaryings(program.id(), GLsizei(varyingNames.size()), varyingNames.data(),
                                GL_INTERLEAVED_ATTRIBS);
  }
  glLinkProgram(program.id());
  deleteShaders();
  GLint linked = 0;
  glGetProgramiv(program.id(), GL_LINK_STATUS, &linked);
  if (!linked) return makeError("cannot link program ({}): {}", names, programLog(program.id()));
  return program;
}

GLint Program::location(std::string_view uniform) const {
  const auto found = locations_.find(uniform);
  if (found != locations_.end()) return found->second;
  const std::string name(uniform);  // first use only: GL needs a NUL-terminated name
  const GLint loc = glGetUniformLocation(id(), name.c_str());
  locations_.emplace(name, loc);
  return loc;
}

void Program::set(std::string_view u, int v) const {
  glProgramUniform1i(id(), location(u), v);
}
void Program::set(std::string_view u, float v) const {
  glProgramUniform1f(id(), location(u), v);
}
void Program::set(std::string_view u, const glm::vec2& v) const {
  glProgramUniform2fv(id(), location(u), 1, glm::value_ptr(v));
}
void Program::set(std::string_view u, const glm::vec3& v) const {
  glProgramUniform3fv(id(), location(u), 1, glm::value_ptr(v));
}
void Program::set(std::string_view u, const glm::vec4& v) const {
  glProgramUniform4fv(id(), location(u), 1, glm::value_ptr(v));
}
void Program::set(std::string_view u, const glm::mat4& v) const {
  glProgramUniformMatrix4fv(id(), location(u), 1, GL_FALSE, glm::value_ptr(v));
}
void Program::set(std::string_view u, const glm::ivec2& v) const {
  glProgramUniform2iv(id(), location(u), 1, glm::value_ptr(v));
}
void Program::set(std::string_view u, const glm::ivec3& v) const {
  glProgramUniform3iv(id(), location(u), 1, glm::value_ptr(v));
}
void Program::setArray(std::string_view u, const int* values, int count) const {
  glProgramUniform1iv(id(), location(u), count, values);
}
void Program::setArray(std::string_view u, const float* values, int count) const {
  glProgramUniform1fv(id(), location(u), count, values);
}
void Program::setArray(std::string_view u, const glm::vec2* values, int count) const {
  glProgramUniform2fv(id(), location(u), count, glm::value_ptr(values[0]));
}
void Program::setArray(std::string_view u, const glm::vec3* values, int count) const {
  glProgramUniform3fv(id(), location(u), count, glm::value_ptr(values[0]));
}
void Program::setArray(std::string_view u, const glm::vec4* values, int count) const {
  glProgramUniform4fv(id(), location(u), count, glm::value_ptr(values[0]));
}
void Program::setArray(std::string_view u, const glm::ivec4* values, int count) const {
  glProgramUniform4iv(id(), location(u), count, glm::value_ptr(values[0]));
}

Status buildComputePrograms(std::initializer_list<ComputeProgram> programs) {
  for (const ComputeProgram& entry : programs) {
    Result<Program> built = Program::fromFiles({{GL_COMPUTE_SHADER, entry.file}});
    if (!built) return built.error();
    *entry.program = std::move(built.value());
  }
  return {};
}

}  // namespace tellus::gl
