#include "tellus/gl/gl_info.hpp"

#include <epoxy/gl.h>
#include <fmt/format.h>

namespace tellus::gl {
namespace {

std::string glString(GLenum name) {
  const auto* text = reinterpret_cast<const char*>(glGetString(name));
  return text ? text : "";
}

int glInt(GLenum name) {
  GLint value = 0;
  glGetIntegerv(name, &value);
  return value;
}

}  // namespace

GlInfo queryGlInfo() {
  GlInfo info;
  info.vendor = glString(GL_VENDOR);
  info.renderer = glString(GL_RENDERER);
  info.version = glString(GL_VERSION);
  info.glslVersion = glString(GL_SHADING_LANGUAGE_VERSION);
  info.maxTextureSize = glInt(GL_MAX_TEXTURE_SIZE);
  info.maxArrayTextureLayers = glInt(GL_MAX_ARRAY_TEXTURE_LAYERS);
  info.max3DTextureSize = glInt(GL_MAX_3D_TEXTURE_SIZE);
  info.maxSamples = glInt(GL_MAX_SAMPLES);
  info.maxComputeWorkGroupInvocations = glInt(GL_MAX_COMPUTE_WORK_GROUP_INVOCATIONS);
  for (GLuint i = 0; i < 3; ++i) {
    glGetIntegeri_v(GL_MAX_COMPUTE_WORK_GROUP_COUNT, i, &info.maxComputeWorkGroupCount[i]);
  }
  info.maxShaderStorageBlockSize = glInt(GL_MAX_SHADER_STORAGE_BLOCK_SIZE);
  info.maxUniformBlockSize = glInt(GL_MAX_UNIFORM_BLOCK_SIZE);
  info.maxTessGenLevel = glInt(GL_MAX_TESS_GEN_LEVEL);
  info.maxGeometryOutputVertices = glInt(GL_MAX_GEOMETRY_OUTPUT_VERTICES);
  info.maxTransformFeedbackBuffers = glInt(GL_MAX_TRANSFORM_FEEDBACK_BUFFERS);
  info.maxVertexAttribs = glInt(GL_MAX_VERTEX_ATTRIBS);
  glGetIntegerv(GL_MAX_VIEWPORT_DIMS, info.maxViewportDims);
  return info;
}

std::string formatGlInfo(const GlInfo& i, const std::string& contextDescription) {
  std::string out;
  const auto line = [&out](std::string_view name, const auto& value) {
    out += fmt::format("{:<34}{}\n", fmt::format("{}:", name), value);
  };
  line("context", contextDescription);
  line("vendor", i.vendor);
  line("renderer", i.renderer);
  line("version", i.version);
  line("GLSL version", i.glslVersion);
  line("max texture size", i.maxTextureSize);
  line("max array texture layers", i.maxArrayTextureLayers);
  line("max 3D texture size", i.max3DTextureSize);
  line("max samples (MSAA)", i.maxSamples);
  line("max viewport", fmt::format("{}x{}", i.maxViewportDims[0], i.maxViewportDims[1]));
  line("max vertex attributes", i.maxVertexAttribs);
  line("max uniform block size (bytes)", i.maxUniformBlockSize);
  line("max SSBO block size (bytes)", i.maxShaderStorageBlockSize);
  line("max compute invocations/group", i.maxComputeWorkGroupInvocations);
  line("max compute work groups",
       fmt::format("{} x {} x {}", i.maxComputeWorkGroupCount[0], i.maxComputeWorkGroupCount[1],
                   i.maxComputeWorkGroupCount[2]));
  line("max tessellation level", i.maxTessGenLevel);
  line("max geometry output vertices", i.maxGeometryOutputVertices);
  line("max transform feedback buffers", i.maxTransformFeedbackBuffers);
  return out;
}

}  // namespace tellus::gl
