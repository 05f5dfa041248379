#include "tellus/render/registry/renderer_option.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

namespace tellus {

std::string optionKey(const RendererOption& option) {
  std::string_view flag = option.flag;
  while (flag.starts_with('-')) flag.remove_prefix(1);
  return std::string(flag);
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

}  // namespace tellus
