#pragma once
// What the current context is: vendor, renderer, version and the limits Tellus cares about.
#include <string>

namespace tellus::gl {

struct GlInfo {
  std::string vendor, renderer, version, glslVersion;
  int maxTextureSize = 0;
  int maxArrayTextureLayers = 0;
  int max3DTextureSize = 0;
  int maxSamples = 0;
  int maxComputeWorkGroupInvocations = 0;
  int maxComputeWorkGroupCount[3] = {0, 0, 0};
  int maxShaderStorageBlockSize = 0;
  int maxUniformBlockSize = 0;
  int maxTessGenLevel = 0;
  int maxGeometryOutputVertices = 0;
  int maxTransformFeedbackBuffers = 0;
  int maxVertexAttribs = 0;
  int maxViewportDims[2] = {0, 0};
};

GlInfo queryGlInfo();  // needs a current context

// Human-readable multi-line report (one "name: value" per line).
std::string formatGlInfo(const GlInfo& info, const std::string& contextDescription);

}  // namespace tellus::gl
