#pragma once
// Running the tellus binary from the CLI tests.
#include <sys/wait.h>

#include <array>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>

#include <fmt/format.h>

#include "support/test_support.hpp"

namespace tellus {

struct RunResult {
  int exitCode = -1;
  std::string output;  // stdout and stderr together
};

// Runs a shell command line, capturing stdout and stderr together.
inline RunResult runShell(const std::string& command) {
  RunResult result;
  FILE* pipe = popen((command + " 2>&1").c_str(), "r");
  if (!pipe) return result;
  std::array<char, 4096> buffer{};
  while (size_t n = fread(buffer.data(), 1, buffer.size(), pipe))
    result.output.append(buffer.data(), n);
  const int status = pclose(pipe);
  result.exitCode = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return result;
}

inline RunResult runTellus(const std::string& arguments) {
  return runShell(fmt::format("'{}' {}", TELLUS_EXECUTABLE, arguments));
}

inline bool haveXvfb() {
  return std::system("command -v xvfb-run >/dev/null 2>&1") == 0;
}

// The viewer in a virtual X server whose screen holds the whole window.
inline RunResult runViewUnderXvfb(const std::string& arguments) {
  return runShell(fmt::format("xvfb-run -a -s '-screen 0 1280x1024x24' '{}' -q view {}",
                              TELLUS_EXECUTABLE, arguments));
}

inline std::string quoted(const std::filesystem::path& path) {
  return fmt::format("'{}'", path.string());
}

inline std::string koreaArguments(const std::filesystem::path& data) {
  std::string args;
  for (const std::filesystem::path& tile : test::koreaMosaicTiles(data)) args += quoted(tile) + " ";
  return args;
}

}  // namespace tellus
