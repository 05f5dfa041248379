// tellus::TerrainView and what it draws with (include/tellus/terrain_view.hpp): a renderer of
// the registry made by name on a Terrain's store, drawing pictures through renderSnapshot.
#include "tellus/terrain_view.hpp"

#include <algorithm>
#include <optional>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "terrain_state.hpp"
#include "tellus/core/camera.hpp"
#include "tellus/core/rgb_image.hpp"
#include "tellus/gl/egl_context.hpp"
#include "tellus/render/output/snapshot.hpp"
#include "tellus/render/registry/renderer_registry.hpp"

namespace tellus {
namespace {

// The renderers this API makes: flat-world ones drawing from the finest grid or the store.
bool offeredByTheApi(const RendererEntry& entry) {
  return entry.world == RendererWorld::Flat && (entry.source == RendererSource::HeightGrid ||
                                               entry.source == RendererSource::TileStore);
}

std::vector<std::string> offeredNames() {
  std::vector<std::string> names;
  for (const RendererEntry* entry : rendererTable()) {
    if (offeredByTheApi(*entry)) names.emplace_back(entry->name);
  }
  return names;
}

// The renderers that stream from the store instead of holding the whole finest grid.
std::string streamingNames() {
  std::vector<std::string> names;
  for (const RendererEntry* entry : rendererTable()) {
    if (offeredByTheApi(*entry) && entry->source == RendererSource::TileStore && !entry->variant)
      names.emplace_back(entry->name);
  }
  return fmt::format("{}", fmt::join(names, ", "));
}

// `options` set into `settings` for the family of `entry`; errors name the option.
Status applyOptions(const RendererEntry& entry, const RendererOptions& options,
                    RendererSettings& settings) {
  const RendererFamily& family = familyOf(entry);
  for (const auto& [name, text] : options) {
    const RendererOption* option = findOption(family.schema, name);
    if (!option) {
      std::vector<std::string> known;
      for (const RendererOption& o : family.schema.options) known.push_back(optionKey(o));
      return makeError("renderer {} has no option '{}'{}{}", entry.name, name,
                       known.empty() ? " (it has none)" : "; it has ", fmt::join(known, ", "));
    }
    auto value = parseOptionValue(*option, text);
    if (!value) return value.error();
    option->set(settings.of(family.schema.family), value.value());
  }
  return Status::success();
}

Camera cameraOf(const Viewpoint& viewpoint) {
  Camera camera;
  camera.position = {viewpoint.x, viewpoint.y, viewpoint.z};
  camera.yawDeg = viewpoint.yawDeg;
  camera.pitchDeg = viewpoint.pitchDeg;
  camera.fovYDeg = viewpoint.fovYDeg;
  return camera;
}

}  // namespace

Viewpoint overviewOf(const Terrain& terrain, double aspect, double yawDeg, double pitchDeg,
                     double fovYDeg) {
  const Camera camera = overviewCamera(terrain.state().bounds, aspect, fovYDeg, pitchDeg, yawDeg);
  return Viewpoint{camera.position.x, camera.position.y, camera.position.z,
                   camera.yawDeg,     camera.pitchDeg,   camera.fovYDeg};
}

std::vector<RendererInfo> listRenderers() {
  std::vector<RendererInfo> list;
  for (const RendererEntry* entry : rendererTable()) {
    if (!offeredByTheApi(*entry)) continue;
    RendererInfo info{std::string(entry->name), std::string(entry->description),
                      std::string(entry->seed), entry->variant, {}};
    const OptionSchema& schema = familyOf(*entry).schema;
    if (schema.defaults) {
      const std::any defaults = schema.defaults();
      for (const RendererOption& option : schema.options) {
        const bool shown = !option.autoDefault && option.kind != OptionKind::Paths;
        info.options.push_back({optionKey(option), option.help, option.unit,
                                shown ? formatOptionValue(option.get(defaults)) : std::string()});
      }
    }
    list.push_back(std::move(info));
  }
  return list;
}

Status Picture::savePng(const std::string& path) const {
  if (width <= 0 || height <= 0 || rgb.size() != std::size_t(width) * std::size_t(height) * 3)
    return makeError("cannot write {}: the picture is {} x {} with {} bytes", path, width, height,
                     rgb.size());
  RgbImage image(width, height);
  image.pixels = rgb;
  return writePng(image, path);
}

// ---- GraphicsContext ---------------------------------------------------------------------

struct GraphicsContext::State {
  std::unique_ptr<gl::GlContext> context;
};

GraphicsContext::GraphicsContext(std::unique_ptr<State> state) : state_(std::move(state)) {}
GraphicsContext::GraphicsContext(GraphicsContext&&) noexcept = default;
GraphicsContext& GraphicsContext::operator=(GraphicsContext&&) noexcept = default;
GraphicsContext::~GraphicsContext() = default;

Result<GraphicsContext> GraphicsContext::createHeadless() {
  auto context = gl::createGlContext({.kind = gl::ContextKind::Headless});
  if (!context) return context.error();
  return GraphicsContext(std::make_unique<State>(State{std::move(context.value())}));
}

// ---- TerrainView --------------------------------------------------------------------------

struct TerrainView::State {
  Terrain terrain;                          // keeps the store open
  std::shared_ptr<const HeightGrid> grid;   // the finest level, for the grid renderers
  std::unique_ptr<TerrainRenderer> renderer;
  std::string name;
  SnapshotOptions snapshot;
  std::optional<OffscreenTarget> target;  // made once, drawn into by every frame
};

TerrainView::TerrainView(std::unique_ptr<State> state) : state_(std::move(state)) {}
TerrainView::TerrainView(TerrainView&&) noexcept = default;
TerrainView& TerrainView::operator=(TerrainView&&) noexcept = default;
TerrainView::~TerrainView() = default;

Result<TerrainView> TerrainView::create(const Terrain& terrain, const std::string& renderer,
                                        const ViewSettings& settings) {
  const RendererEntry* entry = findRenderer(renderer);
  if (!entry || !offeredByTheApi(*entry)) {
    return makeError("unknown renderer '{}' (renderers: {})", renderer,
                     fmt::join(offeredNames(), ", "));
  }
  if (settings.width < 1 || settings.height < 1 || settings.width > 16384 ||
      settings.height > 16384 || settings.samples < 1 || settings.samples > 16) {
    return makeError("view size {} x {} with {} samples: sides must be 1 to 16384, samples 1 to 16",
                     settings.width, settings.height, settings.samples);
  }
  if (!gl::hasCurrentContext()) {
    return makeError("renderer {} needs a current OpenGL context on this thread "
                     "(GraphicsContext::createHeadless(), or the embedder's own)", renderer);
  }
  RendererSettings rendererSettings;
  if (Status applied = applyOptions(*entry, settings.options, rendererSettings); !applied)
    return applied.error();

  auto state = std::make_unique<State>(State{terrain, nullptr, nullptr, renderer, {}, {}});
  const Terrain::State& source = terrain.state();
  RendererInputs inputs;
  inputs.store = source.store;
  if (!source.facts.source.starts_with("http://") && !source.facts.source.starts_with("https://"))
    inputs.inputPath = source.facts.source;
  inputs.waitForTiles = settings.waitForTiles;
  if (entry->source == RendererSource::HeightGrid) {
    auto grid = source.finestGrid(entry->bytesPerSample,
                                  "pick a renderer that streams from the store: " + streamingNames());
    if (!grid) return grid.error();
    state->grid = grid.value();
    inputs.grid = state->grid.get();
  }
  auto made = makeRenderer(renderer, inputs, rendererSettings);
  if (!made) return made.error();
  state->renderer = std::move(made.value());
  state->snapshot.width = settings.width;
  state->snapshot.height = settings.height;
  state->snapshot.samples = settings.samples;
  auto target = OffscreenTarget::create(settings.width, settings.height, settings.samples);
  if (!target) return target.error();
  state->target = std::move(target.value());
  state->snapshot.target = &*state->target;
  return TerrainView(std::move(state));
}

Result<Picture> TerrainView::draw(const Viewpoint& viewpoint, FrameReport* report) {
  const Camera camera = cameraOf(viewpoint);
  if (Status valid = checkCamera(camera); !valid) return valid.error();
  FrameStats stats;
  auto image = renderSnapshot(*state_->renderer, state_->terrain.state().bounds, camera,
                              state_->snapshot, &stats);
  if (!image) return image.error();
  if (report) {
    *report = FrameReport{stats.triangles,     stats.vertices,      stats.drawCalls,
                          stats.tilesWanted,   stats.tilesResident, stats.tilesLoaded,
                          state_->renderer->frameReport()};
  }
  return Picture{image.value().width, image.value().height, std::move(image.value().pixels)};
}

const std::string& TerrainView::renderer() const { return state_->name; }

}  // namespace tellus
