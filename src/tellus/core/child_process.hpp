#pragma once
// Running another program without a shell: the arguments go to it as they are (posix_spawn
// with an argument vector), so quotes, spaces, semicolons or $(...) in a file name are just
// characters of that name, never commands.
#include <string>
#include <vector>

#include "tellus/core/result.hpp"

namespace tellus {

// Runs `arguments[0]` (an absolute path) with `arguments`, its standard streams inherited, and
// waits for it. Succeeds only when it exits with status 0; the error says how it ended.
Status runChildProcess(const std::vector<std::string>& arguments);

}  // namespace tellus
