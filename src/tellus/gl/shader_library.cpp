#include "tellus/gl/shader_library.hpp"

#include <algorithm>
#include <map>
#include <sstream>

#include <fmt/format.h>

namespace tellus::shaders {
const std::map<std::string, std::string_view, std::less<>>& embeddedShaderSources();
}

namespace tellus::gl {
namespace {

Status expand(std::string_view fileName, ExpandedShader& out, int depth) {
  if (depth > 16) return makeError("shader '{}': #include nested too deeply", fileName);
  const auto& sources = shaders::embeddedShaderSources();
  const auto found = sources.find(fileName);
  if (found == sources.end()) return makeError("no embedded shader named '{}'", fileName);
  if (std::find(out.files.begin(), out.files.end(), fileName) != out.files.end()) return {};
  const int fileIndex = int(out.files.size());
  out.files.emplace_back(fileName);
  if (depth > 0) out.source += fmt::format("#line 1 {}\n", fileIndex);  // an included file starts

  std::istringstream lines{std::string(found->second)};
  std::string line;
  int lineNumber = 0;
  while (std::getline(lines, line)) {
    ++lineNumber;
    const size_t start = line.find_first_not_of(" \t");
    if (start != std::string::npos && line.compare(start, 8, "#include") == 0) {
      const size_t open = line.find('"', start), close = line.rfind('"');
      if (open == std::string::npos || close <= open) {
        return makeError("{}:{}: malformed #include", fileName, lineNumber);
      }
      if (Status included = expand(line.substr(open + 1, close - open - 1), out, depth + 1);
          !included) {
        return makeError("{}:{}: {}", fileName, lineNumber, included.error().message);
      }
      out.source += fmt::format("#line {} {}\n", lineNumber + 1, fileIndex);
      continue;
    }
    out.source += line;
    out.source += '\n';
    // After #version (which must come first) start numbering this file's lines.
    if (start != std::string::npos && line.compare(start, 8, "#version") == 0) {
      out.source += fmt::format("#line {} {}\n", lineNumber + 1, fileIndex);
    }
  }
  return {};
}

}  // namespace

Result<ExpandedShader> loadShader(std::string_view fileName) {
  ExpandedShader out;
  if (Status status = expand(fileName, out, 0); !status) return status.error();
  return out;
}

}  // namespace tellus::gl
