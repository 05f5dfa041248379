#pragma once
// The renderers `--algo NAME` can pick. Each algorithm describes itself in its own folder
// (render/<algo>/<algo>_entry.cpp: its rows, option schema and create()); renderer_list.cpp
// lists the families, one line each. The command-line help, `tellus renderers`, the viewer's
// renderer list and panel, the memory check before loading and makeRenderer() read them here.
#include <any>
#include <filesystem>
#include <functional>
#include <map>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "tellus/core/result.hpp"
#include "tellus/render/registry/renderer_option.hpp"
#include "tellus/render/terrain_renderer.hpp"

namespace tellus {

class Geoid;
class GlobalStore;
class StackTerrain;
class TileStore;
struct DrapeImage;
struct HeightGrid;

// The data a renderer draws from; which of them it needs is its row's `source`.
struct RendererInputs {
  const HeightGrid* grid = nullptr;        // full-resolution heights
  std::shared_ptr<const TileStore> store;  // the same terrain as a tile store, when there is one
  // The global store, for the renderers that stream from one (RendererSource::GlobalStore).
  std::shared_ptr<const GlobalStore> globalStore;
  // Stack-terrain renderers: every level of a .tstack (level 0, the finest, first).
  const std::vector<StackTerrain>* stacks = nullptr;
  // Globe renderers: the geoid that turns heights above the geoid into ellipsoidal ones (null:
  // heights are drawn as ellipsoidal), and a colour map draped instead of the hypsometric tint.
  const Geoid* geoid = nullptr;
  const DrapeImage* drape = nullptr;
  // The (first) input's path, for files that lie beside it (RendererOption's
  // besideInputExtension: NAME.ext beside NAME.tstore); empty for a URL.
  std::filesystem::path inputPath;
  // Streaming renderers load every tile a frame needs before drawing it (stills, tests)
  // instead of streaming tiles in over the following frames; RAG reads its pass counts at the
  // end of each frame (no frame drawn from overflowed buffers).
  bool waitForTiles = false;
};

// The world a renderer draws in, and so the cameras it takes.
enum class RendererWorld {
  Flat,   // metres east and north of the DEM's south-west sample (Camera, ViewSetup::create)
  Globe,  // ECEF on the WGS84 ellipsoid (GeoCamera, geoViewSetup)
};

// What a renderer draws from.
enum class RendererSource {
  HeightGrid,    // the full-resolution grid (from any DEM or store)
  TileStore,     // streams from a .tstore
  GlobalStore,   // streams from a global .tstore (tellus build --global)
  StackTerrain,  // material stacks (.tstack, tellus stacks build): 3D terrain
};

struct RendererEntry;
using CreateRenderer = Result<std::unique_ptr<TerrainRenderer>> (*)(
    const RendererEntry& entry, const RendererInputs& inputs, const std::any& options);

// A renderer's factory result as the TerrainRenderer the families' create() return.
template <class Renderer>
Result<std::unique_ptr<TerrainRenderer>> madeRenderer(Result<std::unique_ptr<Renderer>> made) {
  if (!made) return made.error();
  return std::unique_ptr<TerrainRenderer>(std::move(made.value()));
}

// One `--algo` name.
struct RendererEntry {
  std::string_view name;
  std::string_view description;  // one line
  std::string_view seed;         // the seed paper it implements: "000", "004", or "-"
  RendererSource source = RendererSource::HeightGrid;
  // Memory allocated per sample of the full-resolution grid on top of the grid itself, for the
  // memory check before loading (memory_budget.hpp): heights copied to the GPU (system memory
  // on a software rasteriser) and upload staging; 0 for renderers holding a fixed tile budget.
  double bytesPerSample = 0.0;
  // Makes the renderer from the inputs and its family's Options (`options` holds them).
  CreateRenderer create = nullptr;
  RendererWorld world = RendererWorld::Flat;
  // A variant of another row (a seed table's ablation, another tessellation): `--algo all`
  // leaves it out, so that each algorithm appears once.
  bool variant = false;
};

// The renderers sharing one Options struct, as an algorithm's folder declares them.
struct RendererFamily {
  OptionSchema schema;  // family name, defaults and options (none for the references)
  std::vector<RendererEntry> rows;
  // Applies the schema's `live` options to a running renderer of this family; null: none.
  std::function<void(TerrainRenderer&, const std::any& options)> applyLive;
  // What the screen-space error shading mode shows for it (the demo's captions): "the
  // geometric error of the pyramid level each patch reads, an upper bound"; empty: not said.
  std::string_view errorShading;
};

// Every family's Options, as the command line or the panel set them; a family not touched
// yet holds its defaults.
class RendererSettings {
 public:
  // The family's Options (its defaults on first use). An unknown family is a programming
  // error: std::out_of_range.
  std::any& of(std::string_view family);
  const std::any& of(std::string_view family) const;
  template <class Options>
  Options& as(std::string_view family) {
    return std::any_cast<Options&>(of(family));
  }

 private:
  mutable std::map<std::string, std::any, std::less<>> byFamily_;
};

// In list order (renderer_list.cpp).
const std::vector<const RendererFamily*>& rendererFamilies();
const RendererFamily* findRendererFamily(std::string_view family);

std::vector<const RendererEntry*> rendererTable();
// nullptr when there is no such renderer.
const RendererEntry* findRenderer(std::string_view name);
// The family of a row of rendererTable(), and its name (the key of RendererSettings).
const RendererFamily& familyOf(const RendererEntry& entry);
const std::string& familyNameOf(const RendererEntry& entry);

std::vector<std::string_view> rendererNames();
// True for renderers that need RendererInputs::store.
bool rendererNeedsStore(std::string_view name);
// True for renderers that need RendererInputs::globalStore (and no grid).
bool rendererNeedsGlobalStore(std::string_view name);
// True for renderers that draw material stacks (RendererInputs::stacks).
bool rendererNeedsStacks(std::string_view name);
// True for renderers that draw on the globe (they take geo cameras).
bool rendererDrawsGlobe(std::string_view name);
double rendererBytesPerSample(std::string_view name);
// "Renderer: NAME, NAME, ... (`tellus renderers` ...)" for an --algo option's help: the names
// only; `tellus renderers` prints the table.
std::string rendererHelp();

// Needs a current GL context. Errors name the valid choices, or say what input is missing.
Result<std::unique_ptr<TerrainRenderer>> makeRenderer(std::string_view name,
                                                      const RendererInputs& inputs,
                                                      const RendererSettings& settings = {});

// The value of every option of `name`'s family in `settings`, by optionKey() (for the bench's
// report); empty for an unknown name.
std::map<std::string, OptionValue> rendererOptionValues(std::string_view name,
                                                        const RendererSettings& settings);

// A Path option's file: the value, else the input with besideInputExtension (NAME.ext) when
// the option has one and the input is a local file; empty when neither.
std::filesystem::path optionPathOrBesideInput(const RendererOption& option,
                                              const std::any& options,
                                              const std::filesystem::path& inputPath);

}  // namespace tellus
