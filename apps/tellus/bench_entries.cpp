#include "bench_entries.hpp"

#include <algorithm>
#include <set>

#include <fmt/format.h>

#include "cli_support.hpp"

namespace tellus::cli {
namespace {

// The option of `algo`'s family whose key is `key`; nullptr when it has none.
const RendererOption* familyOption(const std::string& algo, const std::string& key) {
  const RendererEntry* entry = findRenderer(algo);
  return entry ? findOption(familyOf(*entry).schema, key) : nullptr;
}

}  // namespace

Result<std::vector<BenchEntry>> benchEntries(const std::vector<std::string>& algos,
                                             const RendererSettings& settings,
                                             const std::string& vary) {
  std::vector<BenchEntry> entries;
  if (vary.empty()) {
    for (const std::string& algo : algos) entries.push_back({algo, algo, settings});
    return entries;
  }
  const std::size_t equals = vary.find('=');
  if (equals == std::string::npos || equals == 0) {
    return makeError("--vary '{}': give OPTION=V1,V2,... (e.g. stack-updates=40,400,0)", vary);
  }
  std::string key = vary.substr(0, equals);
  while (key.starts_with('-')) key.erase(0, 1);
  const std::vector<std::string> values = splitList(vary.substr(equals + 1));
  if (values.empty()) return makeError("--vary '{}': no values after '='", vary);
  if (std::set<std::string>(values.begin(), values.end()).size() != values.size()) {
    return makeError("--vary '{}': a value is given twice", vary);
  }
  bool anyHasIt = false;
  for (const std::string& algo : algos) {
    const RendererOption* option = familyOption(algo, key);
    if (!option) {
      entries.push_back({algo, algo, settings});
      continue;
    }
    if (option->kind == OptionKind::Choices || option->kind == OptionKind::Paths) {
      return makeError("--vary takes an option of one value; {} takes a list", key);
    }
    anyHasIt = true;
    const std::string family = familyNameOf(*findRenderer(algo));
    for (const std::string& text : values) {
      Result<OptionValue> value = parseOptionValue(*option, text);
      if (!value) return makeError("--vary: {}", value.error().message);
      BenchEntry entry{algo, fmt::format("{}[{}={}]", algo, key, text), settings};
      option->set(entry.settings.of(family), value.value());
      entries.push_back(std::move(entry));
    }
  }
  if (!anyHasIt) {
    return makeError("--vary: no renderer of --algo has an option '{}' (`tellus renderers "
                     "--options` lists them)",
                     key);
  }
  return entries;
}

std::vector<std::string> benchLabels(const std::vector<BenchEntry>& entries) {
  std::vector<std::string> labels;
  for (const BenchEntry& entry : entries) labels.push_back(entry.label);
  return labels;
}

}  // namespace tellus::cli
