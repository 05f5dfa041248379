#pragma once
// A renderer family's option schema: each option's flag, help, unit, range and default, and
// where its value lands in the family's own Options struct (RagOptions, RoamOptions...). The
// command line of render, bench and view, the viewer's panel and the bench's JSON are all made
// from the schemas, so an option exists everywhere or nowhere.
//
// A family is the renderers sharing one Options struct: "rag" for rag and rag-right, "rings"
// for the five rings rows. Its Options travel type-erased (std::any) between the command line
// and the family's create(), which is the only code that names the struct.
#include <any>
#include <string_view>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <string>
#include <type_traits>
#include <utility>
#include <variant>
#include <vector>

#include "tellus/core/result.hpp"

namespace tellus {

enum class OptionKind {
  Integer,  // a whole number in [min, max]
  Real,     // a number in [min, max]
  Flag,     // on when given; takes no value
  Choice,   // one of `choices`
  Choices,  // a comma-separated subset of `choices`
  Path,     // a file or folder the renderer reads ("none" on the command line: no file)
  Paths,    // several files (the option repeats)
};

// A value as the command line and the bench's JSON see it: Flag bool, Integer int64, Real
// double, Choice and Path string, Choices and Paths a list.
using OptionValue =
    std::variant<bool, std::int64_t, double, std::string, std::vector<std::string>>;

struct RendererOption {
  std::string flag;                  // "--rag-coarse"
  std::vector<std::string> aliases;  // older spellings still accepted ("--patch-cells")
  std::string label;                 // the panel's short name ("coarse vertices")
  std::string help;                  // one sentence for --help
  std::string unit;                  // "px", "m", "KiB", "ms"; empty for counts and ratios
  OptionKind kind = OptionKind::Integer;
  double min = 0.0, max = 0.0;            // Integer and Real: the accepted range
  double panelMin = 0.0, panelMax = 0.0;  // the panel's slider range (0, 0: the accepted range)
  std::vector<std::string> choices;       // Choice and Choices
  // The default is decided when the renderer is made (the help says how): --help shows none.
  bool autoDefault = false;
  // Path: when not given, the renderer reads the (first) input with this extension if it
  // exists (".ext": NAME.ext beside NAME.tstore).
  std::string besideInputExtension;
  // The viewer can apply it to the running renderer (TerrainRenderer::applyLiveOptions)
  // instead of making a new one.
  bool live = false;
  bool inPanel = true;  // the viewer's panel offers it (Integer, Real, Flag and Choice only)
  std::vector<double> panelSteps;  // the panel offers these values only (a step of a fixed set)
  // The value in the family's Options (held by the std::any), and setting it. `set` takes a
  // value of the kind's alternative, already checked against the range and the choices.
  std::function<OptionValue(const std::any&)> get;
  std::function<void(std::any&, const OptionValue&)> set;
};

struct OptionSchema {
  std::string family;                  // "rag": the settings' key, the flags' prefix
  std::string title;                   // "RAG", for the panel and the help
  std::function<std::any()> defaults;  // the family's Options as they start
  std::vector<RendererOption> options;
};

// The name of an option without its dashes ("rag-coarse"), as the bench's JSON records it.
std::string optionKey(const RendererOption& option);
// The option of `schema` whose optionKey() is `key`; nullptr when it has none.
const RendererOption* findOption(const OptionSchema& schema, std::string_view key);
// "80", "0.35", "on", "globe", "a,b": a value as --help and the panel show it.
std::string formatOptionValue(const OptionValue& value);
// The value of `text` for `option`, checked as the command line checks it: a whole number or a
// finite number in [min, max], "on"/"off" (also true/false, 1/0) for a flag, one of the
// choices (Choices: several, comma-separated), "none" or "" for no file, files that exist for
// Paths (comma-separated). The error names the option, the text and what was expected.
Result<OptionValue> parseOptionValue(const RendererOption& option, std::string_view text);

// ---- Helpers for the families' schemas -----------------------------------------------------
// `access` is a lambda from the family's Options& to a reference to the field it sets.

template <class Options, class Access>
RendererOption numberOption(std::string flag, std::string label, std::string help,
                            std::string unit, double min, double max, Access access) {
  using Field = std::remove_cvref_t<decltype(access(std::declval<Options&>()))>;
  static_assert(std::is_arithmetic_v<Field> && !std::is_same_v<Field, bool>);
  RendererOption option;
  option.flag = std::move(flag);
  option.label = std::move(label);
  option.help = std::move(help);
  option.unit = std::move(unit);
  option.kind = std::is_integral_v<Field> ? OptionKind::Integer : OptionKind::Real;
  option.min = min;
  option.max = max;
  option.get = [access](const std::any& options) -> OptionValue {
    const Field value = access(const_cast<Options&>(std::any_cast<const Options&>(options)));
    if constexpr (std::is_integral_v<Field>) return std::int64_t(value);
    else return double(value);
  };
  option.set = [access](std::any& options, const OptionValue& value) {
    Field& field = access(std::any_cast<Options&>(options));
    if constexpr (std::is_integral_v<Field>) field = Field(std::get<std::int64_t>(value));
    else field = Field(std::get<double>(value));
  };
  return option;
}

// A flag that sets a bool field to `whenGiven` ("--rag-no-clip": earlyClip = false).
template <class Options, class Access>
RendererOption flagOption(std::string flag, std::string label, std::string help, Access access,
                          bool whenGiven = true) {
  RendererOption option;
  option.flag = std::move(flag);
  option.label = std::move(label);
  option.help = std::move(help);
  option.kind = OptionKind::Flag;
  option.get = [access, whenGiven](const std::any& options) -> OptionValue {
    return access(const_cast<Options&>(std::any_cast<const Options&>(options))) == whenGiven;
  };
  option.set = [access, whenGiven](std::any& options, const OptionValue& value) {
    access(std::any_cast<Options&>(options)) = std::get<bool>(value) ? whenGiven : !whenGiven;
  };
  return option;
}

// One of named values of an enum field.
template <class Options, class Enum, class Access>
RendererOption choiceOption(std::string flag, std::string label, std::string help,
                            std::vector<std::pair<std::string, Enum>> names, Access access) {
  RendererOption option;
  option.flag = std::move(flag);
  option.label = std::move(label);
  option.help = std::move(help);
  option.kind = OptionKind::Choice;
  for (const auto& [name, value] : names) option.choices.push_back(name);
  option.get = [access, names](const std::any& options) -> OptionValue {
    const Enum current = access(const_cast<Options&>(std::any_cast<const Options&>(options)));
    for (const auto& [name, value] : names) {
      if (value == current) return name;
    }
    return std::string();
  };
  option.set = [access, names](std::any& options, const OptionValue& value) {
    for (const auto& [name, named] : names) {
      if (name == std::get<std::string>(value)) access(std::any_cast<Options&>(options)) = named;
    }
  };
  return option;
}

// A file or folder (a std::filesystem::path field; empty: none).
template <class Options, class Access>
RendererOption pathOption(std::string flag, std::string label, std::string help, Access access) {
  RendererOption option;
  option.flag = std::move(flag);
  option.label = std::move(label);
  option.help = std::move(help);
  option.kind = OptionKind::Path;
  option.get = [access](const std::any& options) -> OptionValue {
    return access(const_cast<Options&>(std::any_cast<const Options&>(options))).string();
  };
  option.set = [access](std::any& options, const OptionValue& value) {
    access(std::any_cast<Options&>(options)) = std::filesystem::path(std::get<std::string>(value));
  };
  return option;
}

// Several files (a std::vector<std::filesystem::path> field).
template <class Options, class Access>
RendererOption pathsOption(std::string flag, std::string label, std::string help, Access access) {
  RendererOption option;
  option.flag = std::move(flag);
  option.label = std::move(label);
  option.help = std::move(help);
  option.kind = OptionKind::Paths;
  option.get = [access](const std::any& options) -> OptionValue {
    std::vector<std::string> files;
    for (const auto& file : access(const_cast<Options&>(std::any_cast<const Options&>(options))))
      files.push_back(file.string());
    return files;
  };
  option.set = [access](std::any& options, const OptionValue& value) {
    auto& field = access(std::any_cast<Options&>(options));
    field.clear();
    for (const std::string& file : std::get<std::vector<std::string>>(value)) field.emplace_back(file);
  };
  return option;
}

// Type-erases a family's Options type for OptionSchema::defaults.
template <class Options>
std::function<std::any()> defaultsOf() {
  return [] { return std::any(Options{}); };
}

}  // namespace tellus
