#include "tellus/core/logging.hpp"

#include <spdlog/sinks/stdout_color_sinks.h>

namespace tellus {

void initLogging(spdlog::level::level_enum level) {
  auto logger = spdlog::stderr_color_mt("tellus");
  logger->set_pattern("%^%l%$: %v");
  logger->set_level(level);
  spdlog::set_default_logger(logger);
}

}  // namespace tellus
