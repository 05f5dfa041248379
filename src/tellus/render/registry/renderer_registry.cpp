#include "tellus/render/registry/renderer_registry.hpp"

#include <algorithm>
#include <stdexcept>
#include <system_error>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "tellus/render/registry/renderer_list.hpp"

namespace tellus {
namespace {

// The families in list order, and every row, gathered once.
struct Registry {
  std::vector<const RendererFamily*> families = listRendererFamilies();
  std::vector<const RendererEntry*> rows;
  Registry() {
    for (const RendererFamily* family : families) {
      for (const RendererEntry& row : family->rows) rows.push_back(&row);
    }
  }
};

const Registry& registry() {
  static const Registry made;
  return made;
}

}  // namespace

std::any& RendererSettings::of(std::string_view family) {
  auto found = byFamily_.find(family);
  if (found == byFamily_.end()) {
    const RendererFamily* known = findRendererFamily(family);
    if (!known) throw std::out_of_range(fmt::format("no renderer family '{}'", family));
    found = byFamily_.emplace(std::string(family), known->schema.defaults()).first;
  }
  return found->second;
}

const std::any& RendererSettings::of(std::string_view family) const {
  return const_cast<RendererSettings*>(this)->of(family);
}

const std::vector<const RendererFamily*>& rendererFamilies() {
  return registry().families;
}

const RendererFamily* findRendererFamily(std::string_view family) {
  for (const RendererFamily* f : rendererFamilies()) {
    if (f->schema.family == family) return f;
  }
  return nullptr;
}

std::vector<const RendererEntry*> rendererTable() {
  return registry().rows;
}

const RendererEntry* findRenderer(std::string_view name) {
  for (const RendererEntry* row : registry().rows) {
    if (row->name == name) return row;
  }
  return nullptr;
}

const RendererFamily& familyOf(const RendererEntry& entry) {
  for (const RendererFamily* family : rendererFamilies()) {
    for (const RendererEntry& row : family->rows) {
      if (&row == &entry || row.name == entry.name) return *family;
    }
  }
  throw std::out_of_range(fmt::format("renderer '{}' is in no family", entry.name));
}

const std::string& familyNameOf(const RendererEntry& entry) {
  return familyOf(entry).schema.family;
}

std::vector<std::string_view> rendererNames() {
  std::vector<std::string_view> names;
  for (const RendererEntry* entry : registry().rows) names.push_back(entry->name);
  return names;
}

bool rendererNeedsStore(std::string_view name) {
  const RendererEntry* entry = findRenderer(name);
  return entry && entry->source == RendererSource::TileStore;
}

bool rendererNeedsGlobalStore(std::string_view name) {
  const RendererEntry* entry = findRenderer(name);
  return entry && entry->source == RendererSource::GlobalStore;
}

bool rendererNeedsStacks(std::string_view name) {
  const RendererEntry* entry = findRenderer(name);
  return entry && entry->source == RendererSource::StackTerrain;
}

bool rendererDrawsGlobe(std::string_view name) {
  const RendererEntry* entry = findRenderer(name);
  return entry && entry->world == RendererWorld::Globe;
}

double rendererBytesPerSample(std::string_view name) {
  const RendererEntry* entry = findRenderer(name);
  return entry ? entry->bytesPerSample : 0.0;
}

std::string rendererHelp() {
  return fmt::format("Renderer: {} (`tellus renderers` lists them with what each needs)",
                     fmt::join(rendererNames(), ", "));
}

Result<std::unique_ptr<TerrainRenderer>> makeRenderer(std::string_view name,
                                                      const RendererInputs& inputs,
                                                      const RendererSettings& settings) {
  const RendererEntry* entry = findRenderer(name);
  if (!entry) {
    return makeError("unknown renderer '{}' (available: {})", name,
                     fmt::join(rendererNames(), ", "));
  }
  return entry->create(*entry, inputs, settings.of(familyNameOf(*entry)));
}

std::map<std::string, OptionValue> rendererOptionValues(std::string_view name,
                                                        const RendererSettings& settings) {
  std::map<std::string, OptionValue> values;
  const RendererEntry* entry = findRenderer(name);
  if (!entry) return values;
  const std::any& options = settings.of(familyNameOf(*entry));
  for (const RendererOption& option : familyOf(*entry).schema.options) {
    values.emplace(optionKey(option), option.get(options));
  }
  return values;
}

std::filesystem::path optionPathOrBesideInput(const RendererOption& option,
                                              const std::any& options,
                                              const std::filesystem::path& inputPath) {
  const std::string given = std::get<std::string>(option.get(options));
  if (!given.empty()) return given;
  if (option.besideInputExtension.empty() || inputPath.empty()) return {};
  std::filesystem::path beside = inputPath;
  return beside.replace_extension(option.besideInputExtension);
}

}  // namespace tellus
