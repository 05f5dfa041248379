#include "tellus/core/number_fields.hpp"

#include <charconv>
#include <cmath>
#include <string>

#include <fmt/format.h>
#include <fmt/ranges.h>

namespace tellus {

Result<std::vector<double>> parseNumberFields(std::string_view text,
                                              std::span<const char* const> fields,
                                              std::string_view what) {
  const std::string expected = fmt::format("{}", fmt::join(fields, ","));
  std::vector<double> values;
  std::size_t start = 0;
  while (true) {
    const std::size_t comma = text.find(',', start);
    std::string token(
        text.substr(start, comma == std::string_view::npos ? text.npos : comma - start));
    token.erase(0, token.find_first_not_of(" \t"));
    token.erase(token.find_last_not_of(" \t") + 1);
    if (values.size() >= fields.size()) {
      return makeError("{} '{}': expected {} comma-separated numbers {}", what, text,
                       fields.size(), expected);
    }
    double value = 0.0;
    const auto [end, ec] = std::from_chars(token.data(), token.data() + token.size(), value);
    if (token.empty() || ec != std::errc() || end != token.data() + token.size() ||
        !std::isfinite(value)) {
      return makeError("{} '{}': field {} ({}) is not a number: '{}'", what, text,
                       values.size() + 1, fields[values.size()], token);
    }
    values.push_back(value);
    if (comma == std::string_view::npos) break;
    start = comma + 1;
  }
  if (values.size() != fields.size()) {
    return makeError("{} '{}': expected {} comma-separated numbers {}, got {}", what, text,
                     fields.size(), expected, values.size());
  }
  return values;
}

}  // namespace tellus
