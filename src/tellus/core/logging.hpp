#pragma once
// Logging goes to stderr through spdlog ("level: message"). Call initLogging() once in main.
#include <spdlog/spdlog.h>

namespace tellus {

void initLogging(spdlog::level::level_enum level);

}  // namespace tellus
