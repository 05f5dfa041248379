#include "tellus/render/output/snapshot.hpp"

#include <algorithm>
#include <cmath>
#include <optional>

#include <spdlog/spdlog.h>
#include <glm/glm.hpp>

#include "tellus/gl/debug_output.hpp"
#include "tellus/render/imagery/imagery_textures.hpp"

namespace tellus {

Aabb drawnBounds(const HeightGrid& grid, float verticalExaggeration) {
  return drawnBounds(grid.worldBounds(), verticalExaggeration);
}

Aabb drawnBounds(const Aabb& gridBounds, float verticalExaggeration) {
  Aabb bounds = gridBounds;
  bounds.min.z *= verticalExaggeration;
  bounds.max.z *= verticalExaggeration;
  if (bounds.min.z > bounds.max.z) std::swap(bounds.min.z, bounds.max.z);
  return bounds;
}

namespace {

Result<RgbImage> drawSnapshot(TerrainRenderer& renderer, const ViewSetup& view,
                              const SnapshotOptions& options, const RenderSettings& settings,
                              FrameStats* stats) {
  std::optional<OffscreenTarget> made;
  if (!options.target) {
    Result<OffscreenTarget> created =
        OffscreenTarget::create(options.width, options.height, options.samples);
    if (!created) return created.error();
    made = std::move(created.value());
  }
  OffscreenTarget* target = options.target ? options.target : &*made;
  // Draped imagery converges first: a pass reports the pages it wanted, the next draws them
  // (the GPU waited for: a still, not a frame loop).
  constexpr int kMaxImageryPasses = 6;
  FrameStats frame;
  for (int pass = 0;; ++pass) {
    target->begin(skyColour8(settings.shading));
    if (settings.imagery) settings.imagery->beginFrame(true);
    renderer.prepare(view, settings);
    if (auto* reference = dynamic_cast<ReferenceRenderer*>(&renderer)) {
      Progress progress("render", reference->chunkCount() * (settings.wireframe ? 2 : 1));
      frame = reference->draw(view, settings, &progress);
    } else {
      frame = renderer.draw(view, settings);
    }
    if (!settings.imagery) break;
    settings.imagery->endFrame();
    const ImageryPagingInfo& info = settings.imagery->frameInfo();
    if ((pass > 0 && info.pending == 0) || pass + 1 == kMaxImageryPasses) {
      spdlog::debug("imagery: {} pages resident after {} passes, {} still wanted", info.residentPages,
                    pass + 1, info.pending);
      break;
    }
  }
  RgbImage image = target->readRgb();
  gl::checkGlErrors("renderSnapshot");
  if (std::optional<Error> corrupt = renderer.dataError()) return *corrupt;
  spdlog::debug("rendered {} triangles in {} draw calls", frame.triangles, frame.drawCalls);
  if (stats) *stats = frame;
  return image;
}

}  // namespace

Result<RgbImage> renderSnapshot(TerrainRenderer& renderer, const Aabb& bounds, const Camera& camera,
                                const SnapshotOptions& options, FrameStats* stats) {
  const ViewSetup view = ViewSetup::create(camera, bounds, options.width, options.height);
  RenderSettings settings = options.settings;
  if (settings.shading.hazeDensity == 0.0f) {
    settings.shading.fitHazeToView(bounds, camera.position, view.clip.farM);
  }
  return drawSnapshot(renderer, view, options, settings, stats);
}

Result<RgbImage> renderSnapshot(TerrainRenderer& renderer, const ViewSetup& view,
                                const SnapshotOptions& options, FrameStats* stats) {
  RenderSettings settings = options.settings;
  if (settings.shading.hazeDensity == 0.0f) {
    // The nearest terrain is no closer than twice the near plane (geoViewSetup's near is half
    // the clearance): haze starts there and fades the far plane by 30 %.
    const double start = 2.0 * view.clip.nearM;
    settings.shading.hazeStartM = float(start);
    settings.shading.hazeDensity =
        float(-std::log(1.0 - 0.3) / std::max(1.0, view.clip.farM - start));
  }
  return drawSnapshot(renderer, view, options, settings, stats);
}

Result<RgbImage> renderSnapshot(TerrainRenderer& renderer, const HeightGrid& grid,
                                const Camera& camera, const SnapshotOptions& options,
                                FrameStats* stats) {
  return renderSnapshot(renderer, drawnBounds(grid, options.settings.verticalExaggeration), camera,
                        options, stats);
}

}  // namespace tellus
