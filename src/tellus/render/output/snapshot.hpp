#pragma once
// One still image of a terrain from a camera: offscreen target, a renderer, read-back.
// Deterministic: the same grid, camera and options give the same pixels on the same driver.
// Needs a current GL 4.5 context.
#include "tellus/core/rgb_image.hpp"
#include "tellus/render/output/offscreen_target.hpp"
#include "tellus/render/reference/reference_renderer.hpp"

namespace tellus {

struct SnapshotOptions {
  int width = 1280;  // pixels
  int height = 720;
  int samples = 4;          // MSAA samples per pixel
  RenderSettings settings;  // a hazeDensity of 0 means: fitHazeToView() for this view
  // A target of width x height and `samples` to draw into, kept by a caller that draws many
  // stills (tellus::TerrainView); null: one is made for the still.
  OffscreenTarget* target = nullptr;
};

// Terrain bounds in the world frame as drawn (heights scaled by the exaggeration), from the
// grid or from its worldBounds() computed once (a viewer that changes the exaggeration).
Aabb drawnBounds(const HeightGrid& grid, float verticalExaggeration);
Aabb drawnBounds(const Aabb& gridBounds, float verticalExaggeration);

// One frame of any renderer (prepare, then draw). `bounds`: the terrain as drawn (drawnBounds),
// for the clip range and the haze. Streaming renderers should be created to wait for their
// tiles, or the still shows whatever was resident. The reference renderer shows progress.
Result<RgbImage> renderSnapshot(TerrainRenderer& renderer, const Aabb& bounds, const Camera& camera,
                                const SnapshotOptions& options, FrameStats* stats = nullptr);
// The same for a view set up by the caller (globe views: geoViewSetup). A hazeDensity of 0
// starts the haze at twice the near plane and fades the far plane by 30 %.
Result<RgbImage> renderSnapshot(TerrainRenderer& renderer, const ViewSetup& view,
                                const SnapshotOptions& options, FrameStats* stats = nullptr);
// The same with the bounds of `grid`.
Result<RgbImage> renderSnapshot(TerrainRenderer& renderer, const HeightGrid& grid,
                                const Camera& camera, const SnapshotOptions& options,
                                FrameStats* stats = nullptr);

}  // namespace tellus
