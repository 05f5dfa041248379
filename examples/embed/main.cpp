// tellus_embed: the smallest useful program on Tellus's public API. It opens a tile store (a
// file or an http:// URL), makes a headless OpenGL 4.5 context, and renders frames of an orbit
// around the terrain with the rings renderer (seed 000), printing each frame's triangles and
// tiles, and writes the last frame as a PNG.
//
//   tellus_embed STORE OUT.png [FRAMES]
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <string>

#include "tellus/core/camera.hpp"
#include "tellus/core/rgb_image.hpp"
#include "tellus/gl/egl_context.hpp"
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
  if (argc < 3 || argc > 4) {
    std::fprintf(stderr, "usage: tellus_embed STORE OUT.png [FRAMES]\n");
    return 2;
  }
  const std::string storePath = argv[1], outputPath = argv[2];
  const int frames = argc == 4 ? std::atoi(argv[3]) : 8;
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

  // The rings renderer streams tiles on worker threads; stills wait for the tiles they need.
  tellus::RingsOptions options;
  options.waitForTiles = true;
  auto renderer = tellus::RingsRenderer::create(store.value(), options);
  if (!renderer) return failWith("cannot create the rings renderer", renderer.error());

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
    const auto& info = renderer.value()->lastFrame();
    std::printf("frame %d: yaw %.0f deg, %llu triangles, %d patches, %d tiles wanted\n", frame,
                yaw, static_cast<unsigned long long>(stats.triangles), info.visiblePatches,
                info.tilesWanted);
    last = std::move(image.value());
  }
  if (auto written = tellus::writePng(last, outputPath); !written) {
    return failWith("cannot write " + outputPath, written.error());
  }
  std::printf("wrote %s (%dx%d)\n", outputPath.c_str(), last.width, last.height);
  return 0;
}
