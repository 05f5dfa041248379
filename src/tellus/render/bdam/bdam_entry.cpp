// Seed 004's BDAM (`--algo bdam`): row, options, create().
#include "tellus/render/bdam/bdam_renderer.hpp"
#include "tellus/render/registry/renderer_registry.hpp"

namespace tellus {
namespace {

Result<std::unique_ptr<TerrainRenderer>> createBdam(const RendererEntry& entry,
                                                    const RendererInputs& inputs,
                                                    const std::any& given) {
  if (!inputs.grid) return makeError("renderer '{}' needs the height grid", entry.name);
  BdamOptions options = std::any_cast<const BdamOptions&>(given);
  options.name = std::string(entry.name);
  // --bdam-patches, else NAME.bdam beside the input.
  options.patchFile =
      optionPathOrBesideInput(familyOf(entry).schema.options.front(), given, inputs.inputPath);
  return madeRenderer(BdamRenderer::create(*inputs.grid, options));
}

OptionSchema bdamSchema() {
  using O = BdamOptions;
  OptionSchema schema{"bdam", "BDAM", defaultsOf<O>(), {}};
  RendererOption patches = pathOption<O>(
      "--bdam-patches", "patch file",
      "bdam: the patch file (default: NAME.bdam beside the input; 'tellus build --bdam' makes it)",
      [](O& o) -> std::filesystem::path& { return o.patchFile; });
  patches.besideInputExtension = ".bdam";
  RendererOption target = numberOption<O>(
      "--bdam-target", "error target", "bdam: screen-space error target, pixels", "px", 0.01,
      1000.0, [](O& o) -> float& { return o.selection.targetPx; });
  target.panelMin = 0.1;
  target.panelMax = 20.0;
  target.live = true;
  RendererOption cache = numberOption<O>(
      "--bdam-cache", "cache slots",
      "bdam: patches the GPU cache holds at first (grows when a frame needs more)", "", 16,
      1 << 20, [](O& o) -> int& { return o.cacheSlots; });
  cache.panelMin = 256;
  cache.panelMax = 65536;
  RendererOption noCulling = flagOption<O>(
      "--bdam-no-culling", "no culling", "bdam: draw every selected patch, also outside the view",
      [](O& o) -> bool& { return o.selection.culling; }, false);
  RendererOption noExact = flagOption<O>(
      "--bdam-no-exact", "no exact leaves",
      "bdam: the stored leaves are the finest patches drawn (as in the seed); by default a leaf "
      "whose error is still over the target is drawn at the grid's full resolution",
      [](O& o) -> bool& { return o.selection.exactLeaves; }, false);
  // The patch file first: createBdam reads it from there.
  schema.options = {patches, target, cache, noCulling, noExact};
  return schema;
}

// The target applies from the next frame: the next traversal uses it.
void applyLiveBdam(TerrainRenderer& renderer, const std::any& given) {
  if (auto* bdam = dynamic_cast<BdamRenderer*>(&renderer))
    bdam->setTargetPx(std::any_cast<const BdamOptions&>(given).selection.targetPx);
}

}  // namespace

const RendererFamily& bdamRenderers() {
  static const RendererFamily family{
      bdamSchema(),
      {{"bdam",
        "BDAM: a bintree of TIN patches simplified offline with locked borders (tellus build "
        "--bdam), traversed to a screen-space error by diamonds, patches read on demand into a "
        "GPU cache",
        "004", RendererSource::HeightGrid, 4.0, createBdam}},
      applyLiveBdam,
      "the vertical distance from its patches to the height texture under each pixel"};
  return family;
}

}  // namespace tellus
