#include "tellus/render/registry/renderer_option.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <filesystem>
#include <system_error>

#include <fmt/format.h>
#include <fmt/ranges.h>

namespace tellus {
namespace {

// "a,b,c" as its parts ("" gives none).
std::vector<std::string> splitCommas(std::string_view text) {
  std::vector<std::string> parts;
  while (!text.empty()) {
    const std::size_t comma = text.find(',');
    parts.emplace_back(text.substr(0, comma));
    if (comma == std::string_view::npos) break;
    text.remove_prefix(comma + 1);
  }
  return parts;
}

template <class Number>
bool parseWhole(std::string_view text, Number& number) {
  const char* end = text.data() + text.size();
  const auto [stop, error] = std::from_chars(text.data(), end, number);
  return error == std::errc() && stop == end && !text.empty();
}

}  // namespace

std::string optionKey(const RendererOption& option) {
  std::string_view flag = option.flag;
  while (flag.starts_with('-')) flag.remove_prefix(1);
  return std::string(flag);
}

const RendererOption* findOption(const OptionSchema& schema, std::string_view key) {
  for (const RendererOption& option : schema.options) {
    if (optionKey(option) == key) return &option;
  }
  return nullptr;
}

std::string formatOptionValue(const OptionValue& value) {
  struct Formatter {
    std::string operator()(bool on) const { return on ? "on" : "off"; }
    std::string operator()(std::int64_t number) const { return fmt::format("{}", number); }
    std::string operator()(double number) const { return fmt::format("{:g}", number); }
    std::string operator()(const std::string& text) const { return text; }
    std::string operator()(const std::vector<std::string>& list) const {
      return fmt::format("{}", fmt::join(list, ","));
    }
  };
  return std::visit(Formatter{}, value);
}

Result<OptionValue> parseOptionValue(const RendererOption& option, std::string_view text) {
  const auto invalid = [&](std::string_view expected) {
    return makeError("option {}: '{}' is not {}", optionKey(option), text, expected);
  };
  switch (option.kind) {
    case OptionKind::Integer: {
      std::int64_t number = 0;
      if (!parseWhole(text, number) || double(number) < option.min || double(number) > option.max)
        return invalid(fmt::format("a whole number in [{:g}, {:g}]", option.min, option.max));
      return OptionValue(number);
    }
    case OptionKind::Real: {
      double number = 0.0;
      if (!parseWhole(text, number) || !std::isfinite(number) || number < option.min ||
          number > option.max)
        return invalid(fmt::format("a number in [{:g}, {:g}]", option.min, option.max));
      return OptionValue(number);
    }
    case OptionKind::Flag:
      if (text == "on" || text == "true" || text == "1") return OptionValue(true);
      if (text == "off" || text == "false" || text == "0") return OptionValue(false);
      return invalid("on or off");
    case OptionKind::Choice:
    case OptionKind::Choices: {
      std::vector<std::string> picked = splitCommas(text);
      const bool one = option.kind == OptionKind::Choice;
      const bool known = std::ranges::all_of(picked, [&](const std::string& name) {
        return std::ranges::find(option.choices, name) != option.choices.end();
      });
      if (!known || picked.empty() || (one && picked.size() != 1))
        return invalid(fmt::format("{} of {}", one ? "one" : "a comma-separated list",
                                   fmt::join(option.choices, ", ")));
      if (one) return OptionValue(picked.front());
      return OptionValue(std::move(picked));
    }
    case OptionKind::Path:
      return OptionValue(std::string(text == "none" ? std::string_view() : text));
    case OptionKind::Paths: {
      std::vector<std::string> files = splitCommas(text);
      for (const std::string& file : files) {
        std::error_code error;
        if (!std::filesystem::is_regular_file(file, error))
          return makeError("option {}: '{}' is not a file", optionKey(option), file);
      }
      return OptionValue(std::move(files));
    }
  }
  return invalid("a value of this option");
}

}  // namespace tellus
