#pragma once
// Result<T>, Status and Error are public (include/tellus/result.hpp); the library adds
// makeError(), which formats an Error's message with fmt. Library code returns these for bad
// input instead of throwing or exiting; programming bugs are asserts.
#include <utility>

#include <fmt/format.h>

#include "tellus/result.hpp"

namespace tellus {

// Builds an Error from a fmt format string: makeError("cannot open '{}': {}", path, reason).
template <typename... Args>
Error makeError(fmt::format_string<Args...> format, Args&&... args) {
  return Error{fmt::format(format, std::forward<Args>(args)...)};
}

}  // namespace tellus
