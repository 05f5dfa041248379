// tellus renderers: the renderer list, one per line: what `--algo` takes in render, bench and
// view, the world each draws in, what it needs as input, the seed paper it implements.
#include <algorithm>

#include <memory>
#include <vector>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "cli_support.hpp"
#include "tellus/render/registry/renderer_registry.hpp"

namespace tellus::cli {
namespace {

std::string_view worldName(const RendererEntry& entry) {
  if (entry.source == RendererSource::StackTerrain) return "3-D";
  return entry.world == RendererWorld::Globe ? "globe" : "flat";
}

std::string_view inputName(const RendererEntry& entry) {
  switch (entry.source) {
    case RendererSource::TileStore: return "a tile store";
    case RendererSource::GlobalStore: return "a global store";
    case RendererSource::StackTerrain: return "a .tstack";
    case RendererSource::HeightGrid: break;
  }
  return "any DEM or store";
}

// Each family's options, as render, bench and view take them: flag, default, unit, help.
void printOptions() {
  const RendererSettings defaults;
  for (const RendererFamily* family : rendererFamilies()) {
    if (family->schema.options.empty()) continue;
    std::vector<std::string_view> names;
    for (const RendererEntry& row : family->rows) names.push_back(row.name);
    fmt::print("\n{} ({}):\n", family->schema.title, fmt::join(names, ", "));
    for (const RendererOption& option : family->schema.options) {
      const std::string value = formatOptionValue(option.get(defaults.of(family->schema.family)));
      const std::string shown = option.autoDefault ? "auto"
                                : option.kind == OptionKind::Flag ? "off"
                                : value.empty() ? "none"
                                                : value;
      fmt::print("  {:<28} {:>10} {:<4} {}\n", option.flag, shown, option.unit, option.help);
    }
  }
}

int printRenderers(bool withOptions) {
  std::size_t nameWidth = 4, inputWidth = 5;
  for (const RendererEntry* entry : rendererTable()) {
    nameWidth = std::max(nameWidth, entry->name.size());
    inputWidth = std::max(inputWidth, inputName(*entry).size());
  }
  fmt::print("{:<{}}  {:<5}  {:<{}}  {:<4}  {}\n", "name", nameWidth, "world", "input", inputWidth, "seed",
             "what it is");
  for (const RendererEntry* entry : rendererTable()) {
    fmt::print("{:<{}}  {:<5}  {:<{}}  {:<4}  {}{}\n", entry->name, nameWidth, worldName(*entry),
               inputName(*entry), inputWidth, entry->seed, entry->description,
               entry->variant ? " (a variant: --algo all leaves it out)" : "");
  }
  if (withOptions) printOptions();
  return 0;
}

}  // namespace

Command addRenderersCommand(CLI::App& app) {
  CLI::App* sub = app.add_subcommand(
      "renderers", "List the renderers --algo takes (render, bench, view): world, input, seed paper");
  auto withOptions = std::make_shared<bool>(false);
  sub->add_flag("--options", *withOptions,
                "Also list each renderer family's options (render, bench and view take them all) "
                "with their defaults");
  return {sub, [withOptions] { return printRenderers(*withOptions); }, {}};
}

}  // namespace tellus::cli
