// The quality metrics on real renders: the reference renderer scores no cracks and sub-pixel
// error against itself, a full-resolution mesh drawn by the mesh renderer likewise, and a mesh
// with every second row and column dropped in a checkerboard of blocks (T-junctions along the
// block edges) is caught with cracks and a larger error. Proves the metrics can fail; likewise
// the popping metric with a renderer that jumps between levels of detail.
#include <numeric>

#include <gtest/gtest.h>

#include "support/gl_test.hpp"
#include "support/terrain_fixtures.hpp"
#include "support/test_support.hpp"
#include "tellus/dem/dem_loader.hpp"
#include "tellus/dem/terrain_generator.hpp"
#include "tellus/eval/camera_path.hpp"
#include "tellus/eval/frame_metrics.hpp"
#include "tellus/eval/path_benchmark.hpp"
#include "tellus/render/registry/renderer_registry.hpp"
#include "tellus/gl/gpu_frame_timer.hpp"
#include "tellus/render/drawing/mesh_renderer.hpp"
#include "tellus/render/output/named_views.hpp"
#include "tellus/render/output/offscreen_target.hpp"
#include "tellus/render/reference/reference_renderer.hpp"

namespace tellus {
namespace {

constexpr std::uint8_t kSentinel[3] = {255, 0, 255};

class FrameMetricsGpuTest : public test::GlTest {};

HeightGrid roughTerrain() {
  TerrainParams params;
  params.size = 129;
  params.seed = 5;
  params.reliefM = 1500.0;
  return generateTerrain(params);
}

// The grid as triangles; in blocks of `blockCells` cells, every other block (checkerboard)
// uses cells twice as large when `decimate` is set, leaving T-junctions along its edges.
TriangleMesh gridMesh(const HeightGrid& grid, int blockCells, bool decimate) {
  TriangleMesh mesh;
  for (int r = 0; r < grid.height; ++r)
    for (int c = 0; c < grid.width; ++c)
      mesh.positions.emplace_back(float(c * grid.spacingXM),
                                  float((grid.height - 1 - r) * grid.spacingYM), grid.at(c, r));
  const auto index = [&](int c, int r) { return std::uint32_t(r * grid.width + c); };
  for (int by = 0; by * blockCells < grid.height - 1; ++by) {
    for (int bx = 0; bx * blockCells < grid.width - 1; ++bx) {
      const int step = decimate && (bx + by) % 2 == 1 ? 2 : 1;
      for (int r = by * blockCells; r < (by + 1) * blockCells; r += step) {
        for (int c = bx * blockCells; c < (bx + 1) * blockCells; c += step) {
          const std::uint32_t a = index(c, r), b = index(c + step, r);
          const std::uint32_t d = index(c, r + step), e = index(c + step, r + step);
          // The reference renderer's diagonal (north-east to south-west).
          mesh.indices.insert(mesh.indices.end(), {a, d, b, b, d, e});
        }
      }
    }
  }
  return mesh;
}

RendererInputs gridOnly(const HeightGrid& grid) {
  RendererInputs inputs;
  inputs.grid = &grid;
  return inputs;
}

struct Frame {
  RgbImage colour;
  DepthImage depth;
};

Frame renderFrame(TerrainRenderer& renderer, const ViewSetup& view) {
  Result<OffscreenTarget> target = OffscreenTarget::create(view.width, view.height, 1);
  EXPECT_TRUE(target);
  target->begin({kSentinel[0], kSentinel[1], kSentinel[2]});
  renderer.prepare(view, RenderSettings{});
  renderer.draw(view, RenderSettings{});
  return {target->readRgb(), target->readDepth()};
}

TEST_F(FrameMetricsGpuTest, MetricsCatchTJunctionsAndPassCorrectRenderers) {
  const HeightGrid grid = roughTerrain();
  const Aabb bounds = grid.worldBounds();
  const glm::dvec3 centre = bounds.centre();
  const Camera camera =
      cameraLookingAt({centre.x + 300.0, bounds.min.y - 400.0, bounds.max.z + 500.0},
                      {centre.x, centre.y, bounds.min.z}, 50.0);
  const ViewSetup view = ViewSetup::create(camera, bounds, 480, 360);

  Result<ReferenceRenderer> reference = ReferenceRenderer::create(grid);
  ASSERT_TRUE(reference);
  const Frame truth = renderFrame(reference.value(), view);
  const std::vector<std::uint8_t> coverage = coverageFromDepth(truth.depth);
  const std::size_t covered = std::size_t(std::count(coverage.begin(), coverage.end(), 1));
  ASSERT_GT(covered, coverage.size() / 3) << "the terrain should fill much of the frame";

  // The reference against itself: no cracks, sub-pixel error.
  const ScreenSpaceError selfError = measureScreenSpaceError(truth.depth, view, grid);
  EXPECT_EQ(detectCracks(truth.colour, kSentinel, coverage).crackPixels, 0u);
  EXPECT_EQ(selfError.summary.pixels, covered);
  EXPECT_LT(selfError.summary.p95Px, 0.5);
  EXPECT_LT(selfError.summary.maxPx, 1.0);
  EXPECT_LT(measureScreenSpaceError(truth.depth, view, grid).summary.meanPx, 0.05);

  Result<MeshRenderer> meshRenderer = MeshRenderer::create("test-mesh");
  ASSERT_TRUE(meshRenderer) << meshRenderer.error().message;

  // The full-resolution mesh: also no cracks and sub-pixel error.
  ASSERT_TRUE(meshRenderer->upload(gridMesh(grid, 16, false)));
  const Frame full = renderFrame(meshRenderer.value(), view);
  EXPECT_EQ(detectCracks(full.colour, kSentinel, coverage).crackPixels, 0u);
  EXPECT_LT(measureScreenSpaceError(full.depth, view, grid).summary.p95Px, 0.5);

  // The decimated mesh with T-junctions: caught.
  ASSERT_TRUE(meshRenderer->upload(gridMesh(grid, 16, true)));
  const Frame broken = renderFrame(meshRenderer.value(), view);
  const CrackReport cracks = detectCracks(broken.colour, kSentinel, coverage);
  const ScreenSpaceError brokenError = measureScreenSpaceError(broken.depth, view, grid);
  EXPECT_GT(cracks.crackPixels, 10u);
  EXPECT_GT(brokenError.summary.meanPx, 3.0 * selfError.summary.meanPx);
  EXPECT_GT(brokenError.summary.p95Px, 2.0 * selfError.summary.p95Px);
  const std::filesystem::path out = test::testOutputDir();
  ASSERT_TRUE(writePng(markCracks(broken.colour, cracks), out / "t-junction-cracks.png"));
  ASSERT_TRUE(writePng(errorImage(brokenError, view.width, view.height, broken.colour),
                       out / "t-junction-error.png"));
}

}  // namespace
}  // namespace tellus

namespace tellus {
namespace {

class GpuFrameTimerTest : public test::GlTest {};

TEST_F(GpuFrameTimerTest, TimesEveryFrameOnceWithoutStalling) {
  const HeightGrid grid = roughTerrain();
  Result<ReferenceRenderer> renderer = ReferenceRenderer::create(grid);
  ASSERT_TRUE(renderer);
  const Aabb bounds = grid.worldBounds();
  const ViewSetup view = ViewSetup::create(overviewCamera(bounds, 4.0 / 3.0), bounds, 160, 120);
  Result<OffscreenTarget> target = OffscreenTarget::create(160, 120, 1);
  ASSERT_TRUE(target);
  gl::GpuFrameTimer timer(3);  // fewer slots than frames: the ring wraps
  std::vector<std::uint64_t> seen;
  for (std::uint64_t frame = 0; frame < 10; ++frame) {
    target->begin({0, 0, 0});
    timer.beginFrame(frame);
    renderer->draw(view, RenderSettings{});
    timer.endFrame();
    for (const auto& sample : timer.poll()) {
      EXPECT_GT(sample.milliseconds, 0.0);
      seen.push_back(sample.frame);
    }
  }
  for (const auto& sample : timer.finish()) seen.push_back(sample.frame);
  std::sort(seen.begin(), seen.end());
  std::vector<std::uint64_t> all(10);
  std::iota(all.begin(), all.end(), 0);
  EXPECT_EQ(seen, all);
  EXPECT_TRUE(timer.finish().empty());
}

}  // namespace
}  // namespace tellus

namespace tellus {
namespace {

class PathBenchmarkTest : public test::GlTest {};

// The harness end to end: along an orbit, the reference scores no cracks and sub-pixel error;
// the T-junction mesh, judged against the reference's coverage, has cracks in its frames.
TEST_F(PathBenchmarkTest, TheHarnessCatchesTheTJunctionRendererAlongAPath) {
  const HeightGrid grid = roughTerrain();
  Result<CameraPath> path = makeCameraPath("orbit", grid);
  ASSERT_TRUE(path);
  const std::vector<Camera> cameras = path->sample(6);
  PathRunOptions options = test::qualityRun(320, 240, 1);
  options.keepFrames = {0, 5};

  Result<std::unique_ptr<TerrainRenderer>> reference = makeRenderer("reference", gridOnly(grid));
  ASSERT_TRUE(reference);
  Result<PathRun> truth = runPath(*reference.value(), cameras, grid, options);
  ASSERT_TRUE(truth) << truth.error().message;
  ASSERT_EQ(truth->frames.size(), 6u);
  ASSERT_EQ(truth->coverage.size(), 6u);
  for (const FrameRecord& f : truth->frames) {
    EXPECT_EQ(f.crackPixels, 0u);
    EXPECT_GT(f.stats.triangles, 30000u);
    EXPECT_GT(f.gpuMs, 0.0);
    EXPECT_GE(f.frameMs, f.gpuMs);
  }
  EXPECT_LT(truth->errors.percentile(0.95), 0.5);
  EXPECT_LT(truth->errors.max, 1.0);
  EXPECT_EQ(truth->kept.size(), 2u);

  Result<MeshRenderer> broken = MeshRenderer::create("t-junctions");
  ASSERT_TRUE(broken);
  ASSERT_TRUE(broken->upload(gridMesh(grid, 16, true)));
  Result<PathRun> run = runPath(broken.value(), cameras, grid, options, truth->coverage);
  ASSERT_TRUE(run);
  std::uint64_t cracks = 0;
  int crackFrames = 0;
  for (const FrameRecord& f : run->frames) {
    cracks += f.crackPixels;
    crackFrames += f.crackPixels > 0 ? 1 : 0;
  }
  EXPECT_GT(cracks, 20u);
  EXPECT_GE(crackFrames, 3);
  EXPECT_GT(run->errors.mean(), 3.0 * truth->errors.mean());
  // Crack frames keep an image with the cracks marked.
  const bool marked = std::any_of(run->kept.begin(), run->kept.end(), [](const KeptFrame& k) {
    return !k.cracksMarked.pixels.empty();
  });
  EXPECT_TRUE(marked);
}

}  // namespace
}  // namespace tellus

namespace tellus {
namespace {

// A renderer with a deliberate level-of-detail jump: the full grid up to frame `jumpAt`, a grid
// of every 4th sample from then on, whatever the view.
class JumpingRenderer final : public TerrainRenderer {
 public:
  JumpingRenderer(const HeightGrid& grid, int jumpAt) : jumpAt_(jumpAt) {
    HeightGrid coarse((grid.width - 1) / 4 + 1, (grid.height - 1) / 4 + 1);
    coarse.spacingXM = grid.spacingXM * 4.0;
    coarse.spacingYM = grid.spacingYM * 4.0;
    for (int r = 0; r < coarse.height; ++r)
      for (int c = 0; c < coarse.width; ++c) coarse.at(c, r) = grid.at(4 * c, 4 * r);
    for (int i = 0; i < 2; ++i) {
      Result<MeshRenderer> mesh = MeshRenderer::create("jumping");
      EXPECT_TRUE(mesh);
      EXPECT_TRUE(mesh->upload(gridMesh(i == 0 ? grid : coarse, 16, false)));
      meshes_.push_back(std::move(mesh.value()));
    }
  }
  std::string_view name() const override { return "jumping"; }
  FrameStats draw(const ViewSetup& view, const RenderSettings& settings) override {
    previous_ = current_;
    current_ = frame_++ >= jumpAt_ ? 1 : 0;
    return meshes_[std::size_t(current_)].draw(view, settings);
  }
  bool drawPreviousSelection(const ViewSetup& view, const RenderSettings& settings) override {
    if (previous_ < 0) return false;
    meshes_[std::size_t(previous_)].draw(view, settings);
    return true;
  }

 private:
  std::vector<MeshRenderer> meshes_;
  int jumpAt_ = 0, frame_ = 0, current_ = -1, previous_ = -1;
};

// The popping metric catches a deliberate jump from the full grid to a 4x coarser one under a
// still camera, and only in the frame where it happens; the reference never pops.
TEST_F(PathBenchmarkTest, PoppingCatchesADeliberateLevelOfDetailJump) {
  const HeightGrid grid = roughTerrain();
  const Aabb bounds = grid.worldBounds();
  Camera camera;  // low over the terrain, looking across it
  camera.position = {bounds.size().x * 0.3, bounds.size().y * 0.2, bounds.max.z + 200.0};
  camera.yawDeg = 30.0;
  camera.pitchDeg = -25.0;
  camera.fovYDeg = 55.0;
  const std::vector<Camera> still(4, camera);
  const PathRunOptions options = test::qualityRun(320, 240, 0);

  JumpingRenderer jumping(grid, 2);
  Result<PathRun> run = runPath(jumping, still, grid, options);
  ASSERT_TRUE(run) << run.error().message;
  EXPECT_EQ(run->frames[0].popPixels, 0u);  // no earlier frame
  for (int i : {1, 3}) {
    EXPECT_GT(run->frames[std::size_t(i)].popPixels, 10000u) << i;
    EXPECT_EQ(run->frames[std::size_t(i)].popPxMax, 0.0) << i;
  }
  const FrameRecord& jump = run->frames[2];
  EXPECT_GT(jump.popPixels, 10000u);
  EXPECT_GT(jump.popPxP99, 1.0);
  // From an exact surface to a coarse one, the jump is the coarse one's screen-space error.
  EXPECT_NEAR(jump.popPxMean, run->frames[3].ssePxMean, 0.05 * run->frames[3].ssePxMean);
  EXPECT_NEAR(jump.popPxP99, run->frames[3].ssePxP99, 0.05 * run->frames[3].ssePxP99);

  Result<std::unique_ptr<TerrainRenderer>> reference = makeRenderer("reference", gridOnly(grid));
  ASSERT_TRUE(reference);
  Result<PathRun> still_reference = runPath(*reference.value(), still, grid, options);
  ASSERT_TRUE(still_reference);
  for (const FrameRecord& f : still_reference->frames) EXPECT_EQ(f.popPixels, 0u);
}

// Up close the bilinear surface and the drawn triangles differ by metres: the reference must
// be measured against the mesh it draws. A walk in the Japanese Alps catches a mix-up.
TEST_F(PathBenchmarkTest, TheReferenceWalkingThroughRealMountainsIsExact) {
  TELLUS_REQUIRE_SHARED_DATA(data);
  Result<HeightGrid> grid = loadDem({data / "srtm3-hgt-east-asia/N36E137.hgt"});
  ASSERT_TRUE(grid);
  Result<CameraPath> path = makeCameraPath("walk", grid.value());
  ASSERT_TRUE(path);
  PathRunOptions options = test::qualityRun(320, 180, 0);
  Result<std::unique_ptr<TerrainRenderer>> reference =
      makeRenderer("reference", gridOnly(grid.value()));
  ASSERT_TRUE(reference);
  Result<PathRun> run = runPath(*reference.value(), path->sample(4), grid.value(), options);
  ASSERT_TRUE(run) << run.error().message;
  EXPECT_LT(run->errors.mean(), 0.05);
  EXPECT_LT(run->errors.percentile(0.95), 0.1);
}

}  // namespace
}  // namespace tellus
