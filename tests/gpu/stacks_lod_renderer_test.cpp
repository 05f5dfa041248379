// The octree renderer of stack terrain (`stacks`) against the ground truth (stacks-full) along a
// flyover: no crack pixel when every mesh is made at once, nor when at most K are made a frame
// from a pool so small that meshes are evicted (the amortisation keeps the last complete
// selection drawn: never a hole), and the amortisation's delay shows as popping and error.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "support/gl_test.hpp"
#include "support/terrain_fixtures.hpp"
#include "support/stack_fixtures.hpp"
#include "tellus/eval/camera_path.hpp"
#include "tellus/eval/frame_metrics.hpp"
#include "tellus/eval/path_benchmark.hpp"
#include "tellus/render/output/offscreen_target.hpp"
#include "tellus/render/stacks/stacks_full_renderer.hpp"
#include "tellus/render/stacks/stacks_lod_renderer.hpp"
#include "tellus/formats/stacks/stack_aggregation.hpp"
#include "tellus/formats/stacks/stack_generator.hpp"
#include "tellus/formats/stacks/stack_surface.hpp"

namespace tellus {
namespace {

class StacksLodRendererTest : public test::GlTest {
 protected:
  void SetUp() override {
    test::GlTest::SetUp();
    Result<StackTerrain> generated = test::hillsWithCaves({.width = 160,
                                                           .height = 128,
                                                           .amplitudeM = 40.0,
                                                           .waveX = 0.07,
                                                           .waveY = 0.06,
                                                           .riseM = 0.8,
                                                           .caveScaleM = 40.0});
    ASSERT_TRUE(generated) << generated.error().message;
    pyramid_ = buildStackPyramid(std::move(generated.value()));
    Result<CameraPath> path = makeCameraPath("flyover", topSurfaceGrid(pyramid_.front()));
    ASSERT_TRUE(path) << path.error().message;
    cameras_ = path->sample(10);
    options_.width = 240;
    options_.height = 150;
    options_.warmupFrames = 0;
    options_.quality = true;
    options_.recordDepths = true;
    render_.quad.nodeCells = 9;
    render_.cellM = 2.0;
    render_.tauPx = 2.0;  // a small frame: a low threshold to see several levels
    Result<std::unique_ptr<StacksFullRenderer>> full = StacksFullRenderer::create(pyramid_.front(), render_);
    ASSERT_TRUE(full) << full.error().message;
    Result<PathRun> truth = runDepthTruthPath(*full.value(), cameras_, bounds(), options_, nullptr, {});
    ASSERT_TRUE(truth) << truth.error().message;
    truth_ = std::move(truth.value());
    options_.recordDepths = false;
  }

  Aabb bounds() const { return stackWorldBounds(pyramid_.front()); }

  static std::uint64_t cracks(const PathRun& run) {
    std::uint64_t total = 0;
    for (const FrameRecord& f : run.frames) total += f.crackPixels;
    return total;
  }

  std::vector<StackTerrain> pyramid_;
  std::vector<Camera> cameras_;
  PathRunOptions options_;
  StacksRenderOptions render_;
  PathRun truth_;
};

TEST_F(StacksLodRendererTest, EveryMeshAtOnceHasNoCrackAndFewerTriangles) {
  Result<std::unique_ptr<StacksLodRenderer>> lod = StacksLodRenderer::create(pyramid_, render_, true);
  ASSERT_TRUE(lod) << lod.error().message;
  Result<PathRun> run = runDepthTruthPath(*lod.value(), cameras_, bounds(), options_, &truth_.depths, truth_.coverage);
  ASSERT_TRUE(run) << run.error().message;
  EXPECT_EQ(cracks(run.value()), 0u);
  EXPECT_GT(lod.value()->lastFrame().coarsestLevel, lod.value()->lastFrame().finestLevel);
  std::uint64_t lodTriangles = 0, fullTriangles = 0;
  for (const FrameRecord& f : run->frames) lodTriangles += f.stats.triangles;
  for (const FrameRecord& f : truth_.frames) fullTriangles += f.stats.triangles;
  EXPECT_LT(lodTriangles, fullTriangles);
  EXPECT_GT(run->errors.total, 1000u);
}

TEST_F(StacksLodRendererTest, AmortisedUpdatesFromASmallPoolLeaveNoHole) {
  StacksRenderOptions amortised = render_;
  amortised.updatesPerFrame = 4;
  amortised.poolMiB = 1;
  Result<std::unique_ptr<StacksLodRenderer>> lod = StacksLodRenderer::create(pyramid_, amortised, false);
  ASSERT_TRUE(lod) << lod.error().message;
  Result<PathRun> run = runDepthTruthPath(*lod.value(), cameras_, bounds(), options_, &truth_.depths, truth_.coverage);
  ASSERT_TRUE(run) << run.error().message;
  EXPECT_EQ(cracks(run.value()), 0u);
  EXPECT_GT(lod.value()->cache().evictions(), 0u);
  // The limit held for the selections being made (forced meshes aside), and the drawn
  // selection fell behind the newest.
  std::size_t behind = 0;
  for (const FrameRecord& f : run->frames) behind += f.stats.cacheMisses > 0 ? 1 : 0;
  EXPECT_GT(behind, 0u);
}

// Issue 45's levels on a short path at the renderer's defaults (K meshes a frame, geomorph,
// seam band, error threshold; only the node and cell sizes fit this small terrain): the first
// 12 frames of the 200-frame flyover (as the bench flies it; the fixture's 10-frame flyover is a
// time-lapse whose every frame jumps a tenth of the terrain), 480 x 300. No crack, SSE p99
// within a pixel of stacks-full, popping p99 within half a pixel (measured: 0.39 px and 0.01 px).
TEST_F(StacksLodRendererTest, AtItsDefaultsAFlyoverIsSubPixelWithoutPoppingOrCracks) {
  Result<CameraPath> path = makeCameraPath("flyover", topSurfaceGrid(pyramid_.front()));
  ASSERT_TRUE(path) << path.error().message;
  const std::vector<Camera> flyover = path->sample(200);
  const std::vector<Camera> cameras(flyover.begin(), flyover.begin() + 12);
  PathRunOptions options = options_;
  options.width = 480;
  options.height = 300;
  options.recordDepths = true;
  Result<std::unique_ptr<StacksFullRenderer>> full = StacksFullRenderer::create(pyramid_.front(), render_);
  ASSERT_TRUE(full) << full.error().message;
  Result<PathRun> truth = runDepthTruthPath(*full.value(), cameras, bounds(), options, nullptr, {});
  ASSERT_TRUE(truth) << truth.error().message;
  options.recordDepths = false;

  StacksRenderOptions defaults;
  defaults.quad.nodeCells = render_.quad.nodeCells;
  defaults.cellM = render_.cellM;
  Result<std::unique_ptr<StacksLodRenderer>> lod = StacksLodRenderer::create(pyramid_, defaults, false);
  ASSERT_TRUE(lod) << lod.error().message;
  Result<PathRun> run = runDepthTruthPath(*lod.value(), cameras, bounds(), options, &truth->depths, truth->coverage);
  ASSERT_TRUE(run) << run.error().message;
  std::printf("stacks at its defaults: SSE p99 %.3f px, popping p99 %.3f px\n", run->errors.percentile(0.99),
              run->popping.percentile(0.99));
  EXPECT_EQ(cracks(run.value()), 0u);
  EXPECT_GT(run->errors.total, 10000u);
  EXPECT_GT(run->popping.total, 10000u);
  EXPECT_LE(run->errors.percentile(0.99), 1.0);
  EXPECT_LE(run->popping.percentile(0.99), 0.5);
}

// The crack metric's open-air test (drawLastFrameBackFaces) needs the drawn selection to bound
// a closed solid, as the stitched meshes do: every pixel the front faces cover has a back face
// behind it, and back faces show nowhere else but on the outline (where a front and a back
// triangle share a silhouette edge, the rasteriser's tie rule can give an edge pixel to the back
// one only); a back face inside the terrain's image would be a hole.
TEST_F(StacksLodRendererTest, TheStitchedSelectionIsClosedForTheOpenAirTest) {
  Result<std::unique_ptr<StacksLodRenderer>> lod = StacksLodRenderer::create(pyramid_, render_, true);
  ASSERT_TRUE(lod) << lod.error().message;
  for (const Camera& camera : cameras_) {
    const ViewSetup view = ViewSetup::create(camera, bounds(), options_.width, options_.height);
    const test::RenderedFrame front = test::renderFrame(*lod.value(), view);
    Result<OffscreenTarget> target = OffscreenTarget::create(view.width, view.height, 1);
    ASSERT_TRUE(target);
    target->begin({test::kSentinel[0], test::kSentinel[1], test::kSentinel[2]});
    ASSERT_TRUE(lod.value()->drawLastFrameBackFaces(view, {}));
    const std::vector<std::uint8_t> frontCover = coverageFromDepth(front.depth);
    const std::vector<std::uint8_t> backCover = coverageFromDepth(target->readDepth());
    const int w = view.width, h = view.height;
    const auto covered = [&](int x, int y) {
      return x < 0 || y < 0 || x >= w || y >= h || frontCover[std::size_t(y * w + x)] != 0;
    };
    std::size_t terrain = 0, frontOnly = 0, enclosedBackOnly = 0;
    for (int y = 0; y < h; ++y) {
      for (int x = 0; x < w; ++x) {
        const std::size_t i = std::size_t(y * w + x);
        terrain += frontCover[i];
        frontOnly += frontCover[i] && !backCover[i] ? 1 : 0;
        if (frontCover[i] || !backCover[i]) continue;
        bool enclosed = true;
        for (int dy = -1; dy <= 1; ++dy)
          for (int dx = -1; dx <= 1; ++dx) enclosed = enclosed && ((dx == 0 && dy == 0) || covered(x + dx, y + dy));
        enclosedBackOnly += enclosed ? 1 : 0;
      }
    }
    EXPECT_GT(terrain, 100u);
    EXPECT_EQ(frontOnly, 0u) << "camera at " << camera.position.x << ", " << camera.position.y;
    EXPECT_EQ(enclosedBackOnly, 0u) << "camera at " << camera.position.x << ", " << camera.position.y;
  }
}

TEST_F(StacksLodRendererTest, AnEditRemakesEveryAffectedNodeAtOnceWithoutCracks) {
  StacksRenderOptions amortised = render_;
  amortised.updatesPerFrame = 4;
  Result<std::unique_ptr<StacksLodRenderer>> lod = StacksLodRenderer::create(pyramid_, amortised, false);
  ASSERT_TRUE(lod) << lod.error().message;
  StacksLodRenderer& renderer = *lod.value();
  const std::vector<Camera> warm(cameras_.begin(), cameras_.begin() + 3);
  ASSERT_TRUE(runDepthTruthPath(renderer, warm, bounds(), options_, nullptr, {}));
  // A crater where the path looks, and a boulder beside it.
  const Camera& look = cameras_[3];
  const glm::dvec3 ahead = look.position + 60.0 * look.forward();
  const StackTerrain& finest = renderer.pyramid().front();
  const int column = std::clamp(int(ahead.x / finest.spacingM()), 0, finest.width() - 1);
  const int row = std::clamp(finest.height() - 1 - int(ahead.y / finest.spacingM()), 0, finest.height() - 1);
  const double ground = finest.column(column, row).back().topM;
  Result<StacksEditReport> crater =
      renderer.applyEdit({column * finest.spacingM(), (finest.height() - 1 - row) * finest.spacingM(), ground, 14.0, kAir});
  ASSERT_TRUE(crater) << crater.error().message;
  EXPECT_FALSE(crater->region.empty());
  EXPECT_GT(crater->meshesDropped, 0u);
  Result<StacksEditReport> boulder = renderer.applyEdit(
      {column * finest.spacingM() + 30.0, (finest.height() - 1 - row) * finest.spacingM(), ground + 6.0, 8.0, 1});
  ASSERT_TRUE(boulder) << boulder.error().message;
  EXPECT_FALSE(renderer.applyEdit({0, 0, 10, -1, kAir}));  // refused, nothing changed

  // The truth from the edited stacks; the edited renderer and a fresh one on the same stacks.
  const std::vector<Camera> after(cameras_.begin() + 3, cameras_.end());
  Result<std::unique_ptr<StacksFullRenderer>> full = StacksFullRenderer::create(renderer.pyramid().front(), render_);
  ASSERT_TRUE(full);
  PathRunOptions truthOptions = options_;
  truthOptions.recordDepths = true;
  Result<PathRun> truth = runDepthTruthPath(*full.value(), after, bounds(), truthOptions, nullptr, {});
  ASSERT_TRUE(truth);
  Result<PathRun> edited = runDepthTruthPath(renderer, after, bounds(), truthOptions, &truth->depths, truth->coverage);
  ASSERT_TRUE(edited);
  EXPECT_EQ(cracks(edited.value()), 0u);
  Result<std::unique_ptr<StacksLodRenderer>> fresh = StacksLodRenderer::create(renderer.pyramid(), amortised, false);
  ASSERT_TRUE(fresh);
  Result<PathRun> reference = runDepthTruthPath(*fresh.value(), {after.front()}, bounds(), truthOptions, nullptr, {});
  ASSERT_TRUE(reference);
  // The first frame after the strokes: every stale mesh was made again, none is left over.
  ASSERT_EQ(edited->depths.front().depth.size(), reference->depths.front().depth.size());
  std::size_t differing = 0;
  for (std::size_t i = 0; i < reference->depths.front().depth.size(); ++i) {
    differing += edited->depths.front().depth[i] != reference->depths.front().depth[i] ? 1 : 0;
  }
  EXPECT_EQ(differing, 0u);
}


// Geomorphing: the camera jumps closer and stays; without morphing the new selection pops in
// one frame, with it the split nodes slide in over F frames (and nodes about to merge slide
// out first): each frame moves the surface less, and no frame has a crack.
TEST_F(StacksLodRendererTest, GeomorphingSpreadsASwitchOverFramesWithoutCracks) {
  // Straight ahead (what the closer camera sees, the farther one saw: the popping metric
  // compares meshes both frames drew).
  Camera far = cameras_[2];
  far.position -= far.forward() * 200.0;
  std::vector<Camera> cameras{far};
  Camera closer = far;
  closer.position += closer.forward() * 120.0;
  for (int i = 0; i < 8; ++i) cameras.push_back(closer);
  Result<std::unique_ptr<StacksFullRenderer>> full = StacksFullRenderer::create(pyramid_.front(), render_);
  ASSERT_TRUE(full) << full.error().message;
  PathRunOptions options = options_;
  options.recordDepths = true;
  Result<PathRun> truth = runDepthTruthPath(*full.value(), cameras, bounds(), options, nullptr, {});
  ASSERT_TRUE(truth) << truth.error().message;
  options.recordDepths = false;

  struct Outcome {
    std::uint64_t cracks = 0;
    double worstPopMean = 0.0, totalPopMean = 0.0;
    std::size_t morphingFrames = 0;
    std::size_t masksChecked = 0, masksWrong = 0;
  };
  const auto fly = [&](int morphFrames) {
    StacksRenderOptions render = render_;
    render.updatesPerFrame = 0;
    render.morphFrames = morphFrames;
    render.tauPx = 6.0;  // coarser levels within the view: the move changes them
    Result<std::unique_ptr<StacksLodRenderer>> lod = StacksLodRenderer::create(pyramid_, render, false);
    EXPECT_TRUE(lod) << lod.error().message;
    Outcome outcome;
    StacksLodRenderer& renderer = *lod.value();
    Result<PathRun> run = runDepthTruthPath(renderer, cameras, bounds(), options, &truth->depths,
                                            truth->coverage, [&](int) {
                                              if (renderer.lastFrame().morphing > 0) ++outcome.morphingFrames;
                                              const auto masks = renderer.checkMorphMasks();
                                              outcome.masksChecked += masks.checked;
                                              outcome.masksWrong += masks.wrong;
                                            });
    EXPECT_TRUE(run) << run.error().message;
    outcome.cracks = cracks(run.value());
    for (const FrameRecord& f : run->frames) {
      outcome.worstPopMean = std::max(outcome.worstPopMean, f.popPxMean);
      outcome.totalPopMean += f.popPxMean;
    }
    return outcome;
  };
  const Outcome snap = fly(0), morph = fly(4);
  EXPECT_EQ(snap.cracks, 0u);
  EXPECT_EQ(morph.cracks, 0u);
  EXPECT_EQ(snap.morphingFrames, 0u);
  EXPECT_GE(morph.morphingFrames, 3u);
  // The masks worked out beside the selections (on the worker) are those of the drawn one.
  EXPECT_GT(morph.masksChecked, 0u);
  EXPECT_EQ(morph.masksWrong, 0u);
  // The same change, spread: the worst frame moves the surface at most about half as much.
  ASSERT_GT(snap.worstPopMean, 0.0);
  EXPECT_LT(morph.worstPopMean, 0.6 * snap.worstPopMean);
  std::printf("pop mean a frame: worst %.3f / %.3f px, total %.3f / %.3f px; %zu frames morphing\n",
              snap.worstPopMean, morph.worstPopMean, snap.totalPopMean, morph.totalPopMean,
              morph.morphingFrames);
}


// Terrains thinner than the coarser levels' cells, whose surfaces those levels lose.
class StacksLodThinTerrainTest : public test::GlTest {
 protected:
  static std::vector<StackTerrain> thinSlab() {
    constexpr int kSide = 129;
    std::vector<std::vector<StackLayer>> columns;
    for (int y = 0; y < kSide; ++y) {
      for (int x = 0; x < kSide; ++x) {
        const double top = 4.5 + 1.5 * std::sin(x * 0.11) * std::cos(y * 0.07);
        columns.push_back({{0.0f, float(top), 1}});
      }
    }
    Result<StackTerrain> slab = StackTerrain::fromColumns(kSide, kSide, 2.0, columns);
    EXPECT_TRUE(slab) << slab.error().message;
    return slab ? buildStackPyramid(std::move(slab.value())) : std::vector<StackTerrain>{};
  }
  // Rolling ground 20 m thick under a 3 m roof floating 25 m above it over the middle third:
  // the coarser levels smooth the roof away (geometric error: a roof lost) but keep the ground.
  static std::vector<StackTerrain> thinRoof() {
    constexpr int kSide = 129;
    std::vector<std::vector<StackLayer>> columns;
    for (int y = 0; y < kSide; ++y) {
      for (int x = 0; x < kSide; ++x) {
        const float ground = float(20.0 + 3.0 * std::sin(x * 0.11) * std::cos(y * 0.07));
        std::vector<StackLayer> column{{0.0f, ground, 1}};
        if (x > kSide / 3 && x < 2 * kSide / 3 && y > kSide / 3 && y < 2 * kSide / 3) {
          column.push_back({45.0f, 48.0f, 2});
        }
        columns.push_back(column);
      }
    }
    Result<StackTerrain> roof = StackTerrain::fromColumns(kSide, kSide, 2.0, columns);
    EXPECT_TRUE(roof) << roof.error().message;
    return roof ? buildStackPyramid(std::move(roof.value())) : std::vector<StackTerrain>{};
  }
  // A quality run of a 240 x 150 frame, and the small nodes (9 cells of 2 m) both tests draw.
  static PathRunOptions qualityRun() {
    PathRunOptions options;
    options.width = 240;
    options.height = 150;
    options.warmupFrames = 0;
    options.quality = true;
    return options;
  }
  static StacksRenderOptions smallNodes() {
    StacksRenderOptions render;
    render.quad.nodeCells = 9;
    render.cellM = 2.0;
    return render;
  }
  // stacks-full along `cameras`: the depths and coverage the octree renderer is judged against.
  static Result<PathRun> truthAlong(const std::vector<StackTerrain>& pyramid,
                                    const std::vector<Camera>& cameras) {
    Result<std::unique_ptr<StacksFullRenderer>> full =
        StacksFullRenderer::create(pyramid.front(), smallNodes());
    if (!full) return full.error();
    PathRunOptions options = qualityRun();
    options.recordDepths = true;
    return runDepthTruthPath(*full.value(), cameras, stackWorldBounds(pyramid.front()), options,
                             nullptr, {});
  }
};

// A thin terrain (a slab of 3 to 6 m on cells of 2 m: the smoothing loses it from the cells of
// 8 m up) seen from afar: the selection never stops at a level that has lost the surface, so
// the overview shows the terrain stacks-full shows, not the sky through it.
TEST_F(StacksLodThinTerrainTest, TheOverviewOfAThinTerrainIsNotTheSky) {
  const std::vector<StackTerrain> pyramid = thinSlab();
  ASSERT_FALSE(pyramid.empty());
  Result<CameraPath> path = makeCameraPath("orbit", topSurfaceGrid(pyramid.front()));
  ASSERT_TRUE(path) << path.error().message;
  const std::vector<Camera> cameras = path->sample(3);
  Result<PathRun> truth = truthAlong(pyramid, cameras);
  ASSERT_TRUE(truth) << truth.error().message;
  Result<std::unique_ptr<StacksLodRenderer>> lod = StacksLodRenderer::create(pyramid, smallNodes(), true);
  ASSERT_TRUE(lod) << lod.error().message;
  Result<PathRun> run = runDepthTruthPath(*lod.value(), cameras, stackWorldBounds(pyramid.front()),
                                          qualityRun(), &truth->depths, truth->coverage);
  ASSERT_TRUE(run) << run.error().message;
  for (std::size_t i = 0; i < run->frames.size(); ++i) {
    const FrameRecord& frame = run->frames[i];
    std::uint64_t terrain = 0;
    for (std::uint8_t covered : truth->coverage[i]) terrain += covered;
    ASSERT_GT(terrain, 1000u) << "frame " << i << ": the reference sees the terrain";
    EXPECT_GT(frame.stats.triangles, 0u) << "frame " << i;
    // Sky where the reference has terrain: at most a sliver along the silhouette.
    EXPECT_LT(double(frame.crackPixels + frame.silhouettePixels), 0.01 * double(terrain))
        << "frame " << i << ": " << frame.crackPixels << " crack and " << frame.silhouettePixels
        << " silhouette pixels of " << terrain;
  }
}

// A dive onto a thin roof, each frame halving the distance, with few meshes a frame and
// geomorphing: the drawn selection falls behind until a visible node's lost roof spans more
// than the lag bound (4 x the error threshold), and the renderer switches to a whole new
// selection at once. No crack in any frame, and the nodes that slide afterwards use the masks
// of the selection drawn. (The stale-mask crack fixed in 1fd8895 needs a worker's selection
// made beside a drawn selection replaced while it ran; this dive does not reach that timing,
// and passes without the fix too.)
TEST_F(StacksLodThinTerrainTest, ADiveThatTripsTheLagBoundLeavesNoCrack) {
  const std::vector<StackTerrain> pyramid = thinRoof();
  ASSERT_FALSE(pyramid.empty());
  Result<CameraPath> path = makeCameraPath("orbit", topSurfaceGrid(pyramid.front()));
  ASSERT_TRUE(path) << path.error().message;
  const Camera start = path->sample(3).front();
  // Towards the point where the view ray meets the roof's top (48 m up), from 8 km back
  // along the ray, halving the distance each frame down to a few metres.
  const glm::dvec3 target =
      start.position + start.forward() * ((start.position.z - 48.0) / std::max(-start.forward().z, 0.1));
  std::vector<Camera> cameras;
  for (double distance = 8000.0; distance > 3.0; distance *= 0.5) {
    Camera c = start;
    c.position = target - c.forward() * distance;
    cameras.push_back(c);
  }
  Result<PathRun> truth = truthAlong(pyramid, cameras);
  ASSERT_TRUE(truth) << truth.error().message;
  StacksRenderOptions render = smallNodes();
  render.updatesPerFrame = 2;  // far fewer meshes a frame than the dive asks for
  render.morphFrames = 4;
  render.errorTauPx = 2.0;  // the lag bound (4 x this) within reach of a 240 x 150 frame
  Result<std::unique_ptr<StacksLodRenderer>> lod = StacksLodRenderer::create(pyramid, render, false);
  ASSERT_TRUE(lod) << lod.error().message;
  StacksLodRenderer& renderer = *lod.value();
  int lagBoundFrames = 0;
  StacksLodRenderer::MorphMaskCheck masks;
  Result<PathRun> run = runDepthTruthPath(renderer, cameras, stackWorldBounds(pyramid.front()),
                                          qualityRun(), &truth->depths, truth->coverage, [&](int) {
                                            if (renderer.lastFrame().lagBound) ++lagBoundFrames;
                                            const auto checked = renderer.checkMorphMasks();
                                            masks.checked += checked.checked;
                                            masks.wrong += checked.wrong;
                                          });
  ASSERT_TRUE(run) << run.error().message;
  std::printf("lag bound in %d of %zu frames; %zu sliding nodes' masks checked\n", lagBoundFrames,
              cameras.size(), masks.checked);
  EXPECT_GT(lagBoundFrames, 0) << "the dive outruns the amortisation";
  // The nodes that slide after the lag bound's switch (its splits still slide in) slide with
  // the masks of the selection drawn.
  EXPECT_GT(masks.checked, 0u);
  EXPECT_EQ(masks.wrong, 0u);
  for (std::size_t i = 0; i < run->frames.size(); ++i) {
    EXPECT_EQ(run->frames[i].crackPixels, 0u) << "frame " << i;
  }
}

}  // namespace
}  // namespace tellus
