#include "cli_numbers.hpp"

#include <charconv>
#include <cmath>
#include <cstdlib>
#include <optional>
#include <string>

#include <fmt/format.h>

namespace tellus::cli {
namespace {

constexpr const char* kRangeValidator = "tellus-number-range";

// The whole of `text` as a double, or nullopt.
std::optional<double> parseReal(const std::string& text) {
  if (text.empty() || std::isspace(static_cast<unsigned char>(text.front()))) return std::nullopt;
  char* end = nullptr;
  const double value = std::strtod(text.c_str(), &end);
  if (end != text.c_str() + text.size()) return std::nullopt;
  return value;
}

}  // namespace

CLI::Validator numberIn(double lo, double hi) {
  const std::string range = fmt::format("{} to {}", lo, hi);
  return CLI::Validator(
      [lo, hi, range](std::string& text) -> std::string {
        const std::optional<double> value = parseReal(text);
        if (!value) return fmt::format("'{}' is not a number (expected {})", text, range);
        if (!std::isfinite(*value)) {
          return fmt::format("'{}' is not a finite number (expected {})", text, range);
        }
        if (*value < lo || *value > hi) return fmt::format("{} is outside {}", text, range);
        return {};
      },
      range, kRangeValidator);
}

CLI::Validator integerIn(std::int64_t lo, std::int64_t hi) {
  const std::string range = fmt::format("{} to {}", lo, hi);
  return CLI::Validator(
      [lo, hi, range](std::string& text) -> std::string {
        std::int64_t value = 0;
        const char* end = text.data() + text.size();
        const auto [stop, error] = std::from_chars(text.data(), end, value);
        if (error == std::errc::result_out_of_range) {
          return fmt::format("{} is outside {}", text, range);
        }
        if (text.empty() || error != std::errc() || stop != end) {
          return fmt::format("'{}' is not a whole number (expected {})", text, range);
        }
        if (value < lo || value > hi) return fmt::format("{} is outside {}", text, range);
        return {};
      },
      range, kRangeValidator);
}

void requireFiniteNumbers(CLI::App& app) {
  for (CLI::Option* option : app.get_options()) {
    const std::string type = option->get_type_name();
    const bool numeric =
        type.rfind("INT", 0) == 0 || type.rfind("UINT", 0) == 0 || type.rfind("FLOAT", 0) == 0;
    if (!numeric || option->get_expected_min() == 0) continue;
    try {
      option->get_validator();  // any check at all: a range or a list of values
      continue;
    } catch (const CLI::OptionNotFound&) {
    }
    option->check(CLI::Validator(
        [](std::string& text) -> std::string {
          const std::optional<double> value = parseReal(text);
          if (!value || !std::isfinite(*value)) return fmt::format("'{}' is not a finite number", text);
          return {};
        },
        ""));
  }
  for (CLI::App* sub : app.get_subcommands({})) requireFiniteNumbers(*sub);
}

void refuseEmptyValues(CLI::App& app) {
  for (CLI::Option* option : app.get_options()) {
    if (option->get_expected_min() == 0) continue;  // a flag
    // As a transform (that changes nothing): it runs first, before any transform of the
    // option's own turns a word into an empty value ("none" -> "").
    option->transform(CLI::Validator(
        [](std::string& text) -> std::string {
          return text.empty() ? std::string("an empty value; give one, or leave the option out for "
                                            "its default")
                              : std::string();
        },
        ""));
  }
  for (CLI::App* sub : app.get_subcommands({})) refuseEmptyValues(*sub);
}

}  // namespace tellus::cli
