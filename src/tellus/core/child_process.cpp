#include "tellus/core/child_process.hpp"

#include <spawn.h>
#include <sys/wait.h>

#include <cerrno>
#include <csignal>
#include <cstring>

#include <fmt/format.h>

extern char** environ;

namespace tellus {

Status runChildProcess(const std::vector<std::string>& arguments) {
  if (arguments.empty()) return makeError("runChildProcess: no program given");
  std::vector<char*> argv;
  for (const std::string& argument : arguments) argv.push_back(const_cast<char*>(argument.c_str()));
  argv.push_back(nullptr);
  pid_t pid = 0;
  const int spawned = ::posix_spawn(&pid, argv[0], nullptr, nullptr, argv.data(), environ);
  if (spawned != 0) {
    return makeError("cannot run '{}': {}", arguments[0], std::strerror(spawned));
  }
  int status = 0;
  while (::waitpid(pid, &status, 0) < 0) {
    if (errno != EINTR) return makeError("cannot wait for '{}': {}", arguments[0], std::strerror(errno));
  }
  if (WIFEXITED(status) && WEXITSTATUS(status) == 0) return {};
  if (WIFEXITED(status)) {
    return makeError("'{}' failed with exit status {}", arguments[0], WEXITSTATUS(status));
  }
  if (WIFSIGNALED(status)) {
    return makeError("'{}' was killed by signal {} ({})", arguments[0], WTERMSIG(status),
                     strsignal(WTERMSIG(status)));
  }
  return makeError("'{}' ended abnormally", arguments[0]);
}

}  // namespace tellus
