// Seed 001's spiral globe (`--algo spiral`): row, options, create().
#include <cstdint>

#include "tellus/dem/globe_texture_set.hpp"
#include "tellus/render/registry/renderer_registry.hpp"
#include "tellus/render/spiral/spiral_renderer.hpp"

namespace tellus {
namespace {

Result<std::unique_ptr<TerrainRenderer>> createSpiral(const RendererEntry& entry,
                                                      const RendererInputs& inputs,
                                                      const std::any& given) {
  if (!inputs.globalStore) {
    return makeError("renderer '{}' draws a global store: give one built with 'tellus build "
                     "--global SOURCES... -o earth.tstore'",
                     entry.name);
  }
  // Waiting and the geoid follow from the inputs.
  SpiralOptions options = std::any_cast<const SpiralOptions&>(given);
  options.waitForHeights = inputs.waitForTiles;
  options.geoid = inputs.geoid;
  return madeRenderer(SpiralRenderer::create(inputs.globalStore, options));
}

// The fragment shader's features by the names --spiral-without takes (the seed's Table 3).
const std::vector<std::pair<std::string, SpiralFeature>>& featureNames() {
  static const std::vector<std::pair<std::string, SpiralFeature>> names{
      {"clouds", kSpiralClouds},     {"night", kSpiralNightLights},
      {"tangent", kSpiralTangentNormalize}, {"bump", kSpiralBumpMapping},
      {"specular", kSpiralSpecular}, {"diffuse", kSpiralDiffuse}};
  return names;
}

RendererOption withoutOption() {
  RendererOption option;
  option.flag = "--spiral-without";
  option.label = "features off";
  option.help = "spiral: shader features to switch off (the seed's Table 3): clouds, night, "
                "tangent (normalize), bump, specular, diffuse";
  option.kind = OptionKind::Choices;
  for (const auto& [name, bit] : featureNames()) option.choices.push_back(name);
  option.get = [](const std::any& given) -> OptionValue {
    const std::uint32_t features = std::any_cast<const SpiralOptions&>(given).features;
    std::vector<std::string> off;
    for (const auto& [name, bit] : featureNames()) {
      if (!(features & bit)) off.push_back(name);
    }
    return off;
  };
  option.set = [](std::any& given, const OptionValue& value) {
    std::uint32_t& features = std::any_cast<SpiralOptions&>(given).features;
    features = kSpiralAllFeatures;
    for (const std::string& off : std::get<std::vector<std::string>>(value)) {
      for (const auto& [name, bit] : featureNames()) {
        if (name == off) features &= ~std::uint32_t(bit);
      }
    }
  };
  return option;
}

// Each image's GPU texture memory in MiB (the quadtree counts bytes).
RendererOption imageryMemoryOption() {
  RendererOption option;
  option.flag = "--spiral-imagery-memory";
  option.label = "imagery memory";
  option.help = "spiral: GPU memory for each image's textures";
  option.unit = "MiB";
  option.kind = OptionKind::Integer;
  option.min = 1;
  option.max = 65536;
  option.panelMax = 2048;
  option.get = [](const std::any& given) -> OptionValue {
    return std::int64_t(
        std::any_cast<const SpiralOptions&>(given).imageryOptions.quadtree.memoryBudgetBytes >> 20);
  };
  option.set = [](std::any& given, const OptionValue& value) {
    std::any_cast<SpiralOptions&>(given).imageryOptions.quadtree.memoryBudgetBytes =
        std::uint64_t(std::get<std::int64_t>(value)) << 20;
  };
  return option;
}

OptionSchema spiralSchema() {
  using O = SpiralOptions;
  // The Blue Marble set is drawn when it lies beside the working directory.
  OptionSchema schema{"spiral", "Spiral", [] {
                        O options;
                        options.texturesDir = findBlueMarbleSet();
                        return std::any(options);
                      },
                      {}};
  RendererOption spin = numberOption<O>(
      "--spiral-spin-step", "spin step",
      "spiral: spin between vertices, degrees (must divide 360: successive revolutions meet)",
      "deg", 0.1, 120.0, [](O& o) -> double& { return o.spinStepDeg; });
  spin.panelSteps = {1, 2, 3, 4, 5, 6, 8, 9, 10, 12, 15, 18, 20, 24, 30};  // divisors of 360
  RendererOption toDouble = numberOption<O>(
      "--spiral-spin-to-double", "spin to double",
      "spiral: revolutions for the radius to double (the seed's spintodouble)", "", 0.05, 100.0,
      [](O& o) -> double& { return o.spinToDouble; });
  toDouble.panelMin = 1.0;
  toDouble.panelMax = 40.0;
  RendererOption base = numberOption<O>(
      "--spiral-base-radius", "base radius",
      "spiral: the innermost radius, radians of arc (1e-7: 0.64 m)", "rad", 1e-9, 1e-2,
      [](O& o) -> double& { return o.baseRadiusRad; });
  base.inPanel = false;
  RendererOption projection = choiceOption<O, SpiralProjection>(
      "--spiral-projection", "projection", "spiral: the projection the spiral is wrapped onto",
      {{"globe", SpiralProjection::Globe},
       {"flat", SpiralProjection::Flat},
       {"hyperbolic", SpiralProjection::Hyperbolic},
       {"dome", SpiralProjection::Dome}},
      [](O& o) -> SpiralProjection& { return o.projection; });
  RendererOption radii = choiceOption<O, SpiralRadiusMode>(
      "--spiral-radii", "radii",
      "spiral: the drawn radii from occlusion-query feedback (the seed's) or analytically from "
      "the camera",
      {{"feedback", SpiralRadiusMode::Feedback}, {"analytic", SpiralRadiusMode::Analytic}},
      [](O& o) -> SpiralRadiusMode& { return o.radiusMode; });
  RendererOption textures = pathOption<O>(
      "--spiral-textures", "Blue Marble folder",
      "spiral: the NASA Blue Marble folder (colour, altitude, clouds, night lights, water), "
      "converted once to cube maps cached beside the store; 'none': the hypsometric tint "
      "(default: $TELLUS_BLUE_MARBLE or ../shared/data/bluemarble8k-global when there)",
      [](O& o) -> std::filesystem::path& { return o.texturesDir; });
  RendererOption cube = numberOption<O>(
      "--spiral-cube-size", "cube face size",
      "spiral: cube-map texels a face side for the Blue Marble textures", "", 16, 8192,
      [](O& o) -> int& { return o.cubeFaceSize; });
  cube.inPanel = false;
  RendererOption white = flagOption<O>(
      "--spiral-white", "white shader", "spiral: the seed's 'white' fragment shader (Table 1)",
      [](O& o) -> bool& { return o.whiteShader; });
  RendererOption correct = flagOption<O>(
      "--spiral-correct-radius", "radius correction",
      "spiral: the seed's square-root radius correction (larger central triangles)",
      [](O& o) -> bool& { return o.correctRadius; });
  RendererOption blendDepths = flagOption<O>(
      "--spiral-blend-depths", "blend depths",
      "spiral: each vertex's height blended between the two depths its spacing lies between "
      "(default: from one depth, switching at once when its spacing crosses a depth)",
      [](O& o) -> bool& { return o.blendDepths; });
  RendererOption fan = numberOption<O>(
      "--spiral-fan-pixels", "fan target", "spiral: the central fan's target, pixels", "px", 1.0,
      1e6, [](O& o) -> double& { return o.fanPixels; });
  fan.panelMin = 16.0;
  fan.panelMax = 4096.0;
  RendererOption imagery = pathsOption<O>(
      "--spiral-imagery", "imagery",
      "spiral: georeferenced RGB images (GeoTIFF, any CRS; a Landsat scene, decals) draped as "
      "texture quadtrees driven by occlusion queries, built once into "
      "STORE.spiral-textures/NAME.timagery; repeat for several, later on top",
      [](O& o) -> std::vector<std::filesystem::path>& { return o.imagery; });
  RendererOption transfers = numberOption<O>(
      "--spiral-imagery-transfers", "imagery transfers",
      "spiral: texture transfers a frame per image (the seed's smoothing: 1; 0: no cap)", "", 0,
      1000, [](O& o) -> int& { return o.imageryOptions.quadtree.maxTransfersPerUpdate; });
  transfers.panelMax = 16;
  RendererOption levels = flagOption<O>(
      "--spiral-imagery-levels", "imagery levels",
      "spiral: tint the imagery by texel size (the seed's Figure 15: red finest)",
      [](O& o) -> bool& { return o.imageryOptions.showLevels; });
  schema.options = {spin,  toDouble, base,    projection, radii,     textures, cube,
                    withoutOption(), white, correct, blendDepths, fan, imagery, transfers,
                    imageryMemoryOption(), levels};
  return schema;
}

}  // namespace

const RendererFamily& spiralRenderers() {
  static const RendererFamily family{
      spiralSchema(),
      {{"spiral",
        "one static spiral re-centred under the camera and wrapped onto the globe (or flat, "
        "hyperbolic, dome), heights by vertex texture fetch, occlusion-query radii",
        "001", RendererSource::GlobalStore, 0.0, createSpiral, RendererWorld::Globe}},
      {},
      {}};
  return family;
}

}  // namespace tellus
