#pragma once
// Comma-separated numbers with named fields ("x,y,z,yaw,pitch,fov"), as command-line options
// give cameras and brushes. Errors name the option's text, the field and what is wrong.
#include <span>
#include <string_view>
#include <vector>

#include "tellus/core/result.hpp"

namespace tellus {

// Exactly fields.size() finite numbers; `what` names the thing in errors ("camera").
Result<std::vector<double>> parseNumberFields(std::string_view text,
                                              std::span<const char* const> fields,
                                              std::string_view what);

}  // namespace tellus
