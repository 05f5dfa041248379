#include "renderer_cli_options.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "cli_numbers.hpp"

namespace tellus::cli {
namespace {

// "--rag-coarse" and its older spellings, as CLI11 takes several names.
std::string flagNames(const RendererOption& option) {
  std::string names = option.flag;
  for (const std::string& alias : option.aliases) names += "," + alias;
  return names;
}

// The help line: the schema's sentence, the unit, and where a value is given the default.
std::string helpOf(const RendererOption& option) {
  std::string help = option.help;
  if (!option.unit.empty() && (option.kind == OptionKind::Integer || option.kind == OptionKind::Real))
    help += fmt::format(" [{}]", option.unit);
  return help;
}

void addOption(CLI::App* app, const OptionSchema& schema, const RendererOption& option,
               RendererSettings& settings) {
  const std::string family = schema.family;
  const std::string defaultText = formatOptionValue(option.get(settings.of(family)));
  const auto set = [&settings, family, &option](const OptionValue& value) {
    option.set(settings.of(family), value);
  };
  CLI::Option* added = nullptr;
  switch (option.kind) {
    case OptionKind::Integer:
      added = app->add_option_function<std::int64_t>(
                     flagNames(option), [set](std::int64_t v) { set(v); }, helpOf(option))
                  ->check(integerIn(std::int64_t(option.min), std::int64_t(option.max)));
      break;
    case OptionKind::Real:
      added = app->add_option_function<double>(
                     flagNames(option), [set](double v) { set(v); }, helpOf(option))
                  ->check(numberIn(option.min, option.max));
      break;
    case OptionKind::Flag:
      added = app->add_flag_function(
          flagNames(option), [set](std::int64_t) { set(true); }, helpOf(option));
      break;
    case OptionKind::Choice:
      added = app->add_option_function<std::string>(
                     flagNames(option), [set](const std::string& v) { set(v); }, helpOf(option))
                  ->check(CLI::IsMember(option.choices));
      break;
    case OptionKind::Choices:
      added = app->add_option_function<std::vector<std::string>>(
                     flagNames(option), [set](const std::vector<std::string>& v) { set(v); },
                     helpOf(option))
                  ->delimiter(',')
                  ->check(CLI::IsMember(option.choices));
      break;
    case OptionKind::Path:
      added = app->add_option_function<std::string>(
          flagNames(option),
          [set](const std::string& v) { set(v == "none" ? std::string() : v); }, helpOf(option));
      break;
    case OptionKind::Paths:
      added = app->add_option_function<std::vector<std::string>>(
                     flagNames(option), [set](const std::vector<std::string>& v) { set(v); },
                     helpOf(option))
                  ->check(CLI::ExistingFile);
      break;
  }
  added->group(schema.title + " options");
  const bool showDefault = option.kind != OptionKind::Flag && option.kind != OptionKind::Paths &&
                           !option.autoDefault && !defaultText.empty();
  if (showDefault) added->default_str(defaultText);
}

}  // namespace

void addRendererOptions(CLI::App* app, RendererSettings& settings) {
  for (const RendererFamily* family : rendererFamilies()) {
    for (const RendererOption& option : family->schema.options) {
      addOption(app, family->schema, option, settings);
    }
  }
}

}  // namespace tellus::cli
