// Seed 002's RINGO (`--algo ringo`): row, options, create().
#include "tellus/render/registry/renderer_registry.hpp"
#include "tellus/render/ringo/ringo_renderer.hpp"

namespace tellus {
namespace {

Result<std::unique_ptr<TerrainRenderer>> createRingo(const RendererEntry& entry,
                                                     const RendererInputs& inputs,
                                                     const std::any& given) {
  if (!inputs.globalStore) {
    return makeError("renderer '{}' streams from a global store: give one built with 'tellus "
                     "build --global SOURCES... -o earth.tstore'",
                     entry.name);
  }
  // Waiting and the geoid follow from the inputs.
  RingoOptions options = std::any_cast<const RingoOptions&>(given);
  options.waitForBlocks = inputs.waitForTiles;
  options.geoid = inputs.geoid;
  return madeRenderer(RingoRenderer::create(inputs.globalStore, options));
}

OptionSchema ringoSchema() {
  using O = RingoOptions;
  OptionSchema schema{"ringo", "RINGO", defaultsOf<O>(), {}};
  RendererOption rings = numberOption<O>(
      "--ringo-rings", "rings", "RINGO: rings of blocks around the central 3 x 3 (the seed's test: 4)",
      "", 0, 8, [](O& o) -> int& { return o.rings; });
  RendererOption horizon = numberOption<O>(
      "--ringo-blocks-to-horizon", "blocks to horizon",
      "RINGO: the block size, as the distance to the horizon over this many blocks (more: "
      "smaller, finer blocks)",
      "", 0.5, 100.0, [](O& o) -> double& { return o.blocksToHorizon; });
  horizon.panelMin = 1.0;
  horizon.panelMax = 20.0;
  RendererOption upload = numberOption<O>(
      "--ringo-upload-kib", "upload / frame", "RINGO: vertex data copied into GPU buffers per frame",
      "KiB", 1, 1 << 20, [](O& o) -> int& { return o.uploadKiBPerFrame; });
  upload.panelMin = 64;
  upload.panelMax = 16384;
  RendererOption threads = numberOption<O>(
      "--ringo-threads", "threads", "RINGO: reorganisation worker threads at most (0: every core)",
      "", 0, 1024, [](O& o) -> int& { return o.threads; });
  threads.panelMax = 16;
  RendererOption morph = numberOption<O>(
      "--ringo-morph-frames", "morph frames",
      "RINGO: frames over which a matrix of a new depth morphs from the surface drawn before it "
      "(0: it replaces it at once)",
      "", 0, 1000, [](O& o) -> int& { return o.morphFrames; });
  morph.panelMax = 60;
  schema.options = {rings, horizon, upload, threads, morph};
  return schema;
}

}  // namespace

const RendererFamily& ringoRenderers() {
  static const RendererFamily family{
      ringoSchema(),
      {{"ringo",
        "nested rings of blocks on the WGS84 ellipsoid, static GPU buffers, parallel "
        "reorganisation",
        "002", RendererSource::GlobalStore, 0.0, createRingo, RendererWorld::Globe}},
      {},
      {}};
  return family;
}

}  // namespace tellus
