#pragma once
// The GLSL sources of shaders/, embedded into the binary at build time
// (cmake/TellusEmbedShaders.cmake). A line `#include "path"` inside a shader is replaced by
// that file (once per file), with #line directives so compiler messages point at the right
// file: source-string number i stands for the i-th file listed in ExpandedShader::files.
#include <string>
#include <string_view>
#include <vector>

#include "tellus/core/result.hpp"

namespace tellus::gl {

struct ExpandedShader {
  std::string source;
  std::vector<std::string> files;  // files[i] is GLSL source-string number i
};

Result<ExpandedShader> loadShader(std::string_view fileName);

}  // namespace tellus::gl
