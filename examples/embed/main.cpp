// tellus_embed: the smallest useful program on Tellus's public API. It opens a tile store (a
// file or an http:// URL), makes a headless OpenGL 4.5 context, and renders frames of an orbit
// around the terrain with a renderer picked by name (default rings, seed 000; any name of
// `tellus renderers` that draws from a store or a grid), printing each frame's triangles and
// what the renderer says of its frame, and writes the last frame as a PNG.
//
//   tellus_embed STORE OUT.png [FRAMES] [RENDERER]
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <string>

#include "tellus/core/camera.hpp"
#include "tellus/core/rgb_image.hpp"
#include "tellus/gl/egl_context.hpp"
#include "tellus/render/registry/renderer_registry.hpp"
#include "tellus/render/rings/rings_renderer.hpp"
#include "tellus/render/output/snapshot.hpp"
#include "tellus/tiles/tile_store.hpp"

namespace {

int failWith(const std::string& what, const tellus::Error& error) {
  std::fprintf(stderr, "tellus_embed: %s: %s\n", what.c_str(), error.message.c_str());
  return 1;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 3 || argc > 5) {
    std::fprintf(stderr, "usage: tellus_embed STORE OUT.png [FRAMES] [RENDERER]\n");
    return 2;
  }
  const std::string storePath = argv[1], outputPath = argv[2];
  const int frames = argc >= 4 ? std::atoi(argv[3]) : 8;
  const std::string algo = argc == 5 ? argv[4] : "rings";
  if (frames < 1 || frames > 10000) {
    std::fprintf(stderr, "tellus_embed: FRAMES must be 1 to 10000, not '%s'\n", argv[3]);
    return 2;
  }

  // The store: its coarsest level gives the terrain's box in the world frame.
  auto store = tellus::TileStore::open(storePath);
  if (!store) return failWith("cannot open the store", store.error());
  const int coarsest = store.value()->layout().levelCount() - 1;
  auto overview = tellus::readStoreLevel(*store.value(), coarsest);
  if (!overview) return failWith("cannot read the coarsest level", overview.error());
  const tellus::Aabb bounds = tellus::drawnBounds(overview.value(), 1.0f);

  // A headless GL 4.5 context (EGL), current on this thread from now on.
  auto context = tellus::gl::createEglContext();
  if (!context) return failWith("no OpenGL 4.5 context", context.error());

  // A renderer by name from the registry. The streaming ones load tiles on worker threads;
  // stills wait for the tiles they need. Options are each family's own struct: here the rings'
  // GPU cache, as --rings-gpu-slots sets it on the command line.
  auto finest = tellus::readStoreLevel(*store.value(), 0);  // the grid renderers draw from
  if (!finest) return failWith("cannot read the finest level", finest.error());
  tellus::RendererInputs inputs;
  inputs.grid = &finest.value();
  inputs.store = store.value();
  inputs.inputPath = storePath;
  inputs.waitForTiles = true;
  tellus::RendererSettings settings;
  settings.as<tellus::RingsOptions>("rings").gpuSlots = 64;
  auto renderer = tellus::makeRenderer(algo, inputs, settings);
  if (!renderer) return failWith("cannot create renderer " + algo, renderer.error());

  tellus::SnapshotOptions snapshot;
  snapshot.width = 640;
  snapshot.height = 360;
  tellus::RgbImage last;
  for (int frame = 0; frame < frames; ++frame) {
    // An orbit: the overview camera turned a full circle over the frames.
    const double yaw = 360.0 * frame / frames;
    tellus::Camera camera = tellus::overviewCamera(bounds, 16.0 / 9.0, 40.0, -35.0, yaw);
    tellus::FrameStats stats;
    auto image = tellus::renderSnapshot(*renderer.value(), bounds, camera, snapshot, &stats);
    if (!image) return failWith("cannot render a frame", image.error());
    std::printf("frame %d: yaw %.0f deg, %llu triangles, %llu tiles wanted\n", frame, yaw,
                static_cast<unsigned long long>(stats.triangles),
                static_cast<unsigned long long>(stats.tilesWanted));
    for (const std::string& line : renderer.value()->frameReport()) std::printf("  %s\n", line.c_str());
    last = std::move(image.value());
  }
  if (auto written = tellus::writePng(last, outputPath); !written) {
    return failWith("cannot write " + outputPath, written.error());
  }
  std::printf("wrote %s (%dx%d)\n", outputPath.c_str(), last.width, last.height);
  return 0;
}
