// Seed 004's geometry image warping (`--algo giw`): row, options, create().
#include "tellus/render/giw/giw_renderer.hpp"
#include "tellus/render/registry/renderer_registry.hpp"

namespace tellus {
namespace {

Result<std::unique_ptr<TerrainRenderer>> createGiw(const RendererEntry& entry,
                                                   const RendererInputs& inputs,
                                                   const std::any& given) {
  if (!inputs.grid) return makeError("renderer '{}' needs the height grid", entry.name);
  GiwOptions options = std::any_cast<const GiwOptions&>(given);
  options.name = std::string(entry.name);
  return madeRenderer(GiwRenderer::create(*inputs.grid, options));
}

OptionSchema giwSchema() {
  using O = GiwOptions;
  OptionSchema schema{"giw", "Geometry image warping", defaultsOf<O>(), {}};
  RendererOption size = numberOption<O>(
      "--giw-size", "geometry image size", "giw: geometry image side, vertices (the warped quad mesh)",
      "", 9, 2049, [](O& o) -> int& { return o.settings.size; });
  size.panelMin = 33;
  size.panelMax = 1025;
  RendererOption slope = numberOption<O>(
      "--giw-slope", "slope weight",
      "giw: importance of steep over flat ground (0: distance and frustum only)", "", 0.0, 1000.0,
      [](O& o) -> float& { return o.settings.slopeWeight; });
  slope.panelMax = 32.0;
  slope.live = true;
  RendererOption uniform = numberOption<O>(
      "--giw-uniform", "uniform share",
      "giw: share of each row's and column's samples kept evenly spread", "", 0.0, 1.0,
      [](O& o) -> float& { return o.settings.uniformShare; });
  schema.options = {size, slope, uniform};
  return schema;
}

// The slope weight applies from the next frame: the next warp uses it.
void applyLiveGiw(TerrainRenderer& renderer, const std::any& given) {
  if (auto* giw = dynamic_cast<GiwRenderer*>(&renderer))
    giw->setSlopeWeight(std::any_cast<const GiwOptions&>(given).settings.slopeWeight);
}

}  // namespace

const RendererFamily& giwRenderers() {
  static const RendererFamily family{
      giwSchema(),
      {{"giw",
        "geometry image warping: a quad mesh over the view's footprint warped each frame by an "
        "importance map (distance, slope, frustum), rows then columns, sent to the GPU each frame",
        "004", RendererSource::HeightGrid, 4.0, createGiw}},
      applyLiveGiw,
      "the vertical distance from its warped grid to the height texture under each pixel"};
  return family;
}

}  // namespace tellus
