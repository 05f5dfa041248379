#include "tellus/render/snapshot.hpp"

#include <spdlog/spdlog.h>
#include <glm/glm.hpp>

#include "tellus/gl/debug_output.hpp"

namespace tellus {

Aabb drawnBounds(const HeightGrid& grid, float verticalExaggeration) {
  Aabb bounds = grid.worldBounds();
  bounds.min.z *= verticalExaggeration;
  bounds.max.z *= verticalExaggeration;
  if (bounds.min.z > bounds.max.z) std::swap(bounds.min.z, bounds.max.z);
  return bounds;
}

Result<RgbImage> renderSnapshot(ReferenceRenderer& renderer, const HeightGrid& grid,
                                const Camera& camera, const SnapshotOptions& options,
                                FrameStats* stats) {
  Result<OffscreenTarget> target =
      OffscreenTarget::create(options.width, options.height, options.samples);
  if (!target) return target.error();
  const Aabb bounds = drawnBounds(grid, options.settings.verticalExaggeration);
  const ViewSetup view = ViewSetup::create(camera, bounds, options.width, options.height);
  RenderSettings settings = options.settings;
  if (settings.shading.hazeDensity == 0.0f) {
    settings.shading.fitHazeToView(bounds, camera.position, view.clip.farM);
  }
  target->begin(skyColour8(settings.shading));
  Progress progress("render", renderer.chunkCount() * (settings.wireframe ? 2 : 1));
  const FrameStats frame = renderer.draw(view, settings, &progress);
  RgbImage image = target->readRgb();
  gl::checkGlErrors("renderSnapshot");
  spdlog::debug("rendered {} triangles in {} draw calls", frame.triangles, frame.drawCalls);
  if (stats) *stats = frame;
  return image;
}

}  // namespace tellus
