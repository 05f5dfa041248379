// tellus renderers: the renderer list, one per line: what `--algo` takes in render, bench and
// view, the world each draws in, what it needs as input, the seed paper it implements.
#include <algorithm>

#include <fmt/format.h>

#include "cli_support.hpp"
#include "tellus/eval/renderer_registry.hpp"

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

int printRenderers() {
  std::size_t nameWidth = 4, inputWidth = 5;
  for (const RendererEntry& entry : rendererTable()) {
    nameWidth = std::max(nameWidth, entry.name.size());
    inputWidth = std::max(inputWidth, inputName(entry).size());
  }
  fmt::print("{:<{}}  {:<5}  {:<{}}  {:<4}  {}\n", "name", nameWidth, "world", "input", inputWidth, "seed",
             "what it is");
  for (const RendererEntry& entry : rendererTable()) {
    fmt::print("{:<{}}  {:<5}  {:<{}}  {:<4}  {}{}\n", entry.name, nameWidth, worldName(entry),
               inputName(entry), inputWidth, entry.seed, entry.description,
               entry.variant ? " (a variant: --algo all leaves it out)" : "");
  }
  return 0;
}

}  // namespace

Command addRenderersCommand(CLI::App& app) {
  CLI::App* sub = app.add_subcommand(
      "renderers", "List the renderers --algo takes (render, bench, view): world, input, seed paper");
  return {sub, [] { return printRenderers(); }, {}};
}

}  // namespace tellus::cli
