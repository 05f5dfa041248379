// The spiral globe (seed 001) on a synthetic global store: the vertex shader places every drawn
// vertex where the CPU twin does (spiral_projection.hpp, spiral_height_levels.hpp), in every
// projection; the ground has no holes from orbit or near it, nor where the spiral meets its fan;
// the drawn spiral near the ground is the store's surface; the occlusion-query feedback settles
// the radii on a still camera and follows a zoom.
#include <cmath>
#include <numbers>

#include <gtest/gtest.h>
#include <glm/geometric.hpp>

#include "support/gl_test.hpp"
#include "support/globe_fixtures.hpp"
#include "support/imagery_fixtures.hpp"
#include "support/terrain_fixtures.hpp"
#include "support/test_support.hpp"
#include "tellus/core/geo_camera.hpp"
#include "tellus/core/geodesy.hpp"
#include "tellus/core/rgb_image.hpp"
#include "tellus/render/globe/globe_reference_renderer.hpp"
#include "tellus/render/output/offscreen_target.hpp"
#include "tellus/render/spiral/spiral_renderer.hpp"
#include "tellus/viewer/globe_camera.hpp"

namespace tellus {
namespace {

using SpiralRendererTest = test::GlTest;

std::unique_ptr<SpiralRenderer> makeSpiral(SpiralOptions options = {}) {
  options.waitForHeights = true;
  Result<std::unique_ptr<SpiralRenderer>> spiral =
      SpiralRenderer::create(test::syntheticEarth(), options);
  EXPECT_TRUE(spiral) << spiral.error().message;
  return spiral ? std::move(spiral.value()) : nullptr;
}

ViewSetup viewFrom(const GeoCamera& camera, int width, int height) {
  return geoViewSetup(camera, chooseGeoClipRange(camera, 0.0, 2000.0), width, height);
}

TEST_F(SpiralRendererTest, TheVertexShaderPlacesVerticesWhereTheCpuTwinDoes) {
  // Transform feedback needs a complete framebuffer bound, even with rasterisation off.
  Result<OffscreenTarget> target = OffscreenTarget::create(16, 16, 1);
  ASSERT_TRUE(target) << target.error().message;
  target->begin({0, 0, 0});
  for (SpiralProjection projection : {SpiralProjection::Globe, SpiralProjection::Flat,
                                      SpiralProjection::Hyperbolic, SpiralProjection::Dome}) {
    for (bool correct : {false, true}) {
      SpiralOptions options;
      options.projection = projection;
      options.correctRadius = correct;
      options.blendDepths = correct;  // the blended heights' twin too, on every projection
      options.radiusMode = SpiralRadiusMode::Analytic;
      std::unique_ptr<SpiralRenderer> spiral = makeSpiral(options);
      ASSERT_TRUE(spiral);
      for (const GeoCamera& camera : {GeoCamera{41.9, 11.7, 3000.0, 30.0, -20.0, 60.0},
                                      GeoCamera{30.0, 20.0, 8e6, 0.0, -90.0, 40.0}}) {
        const ViewSetup view = viewFrom(camera, 160, 120);
        spiral->prepare(view, {});
        const std::vector<glm::vec3> gpu = spiral->captureDrawnPositions(view);
        const std::vector<glm::vec3> cpu = spiral->referenceDrawnPositions(view);
        ASSERT_EQ(gpu.size(), cpu.size());
        ASSERT_GT(cpu.size(), 300u);
        int far = 0;
        double worstNear = 0.0;
        for (std::size_t k = 0; k < cpu.size(); ++k) {
          const double distance = glm::length(glm::dvec3(cpu[k]));
          const double error = glm::length(glm::dvec3(gpu[k]) - glm::dvec3(cpu[k]));
          // GPU and CPU floats differ in their last bits, and the GPU's sin, cos and atan
          // (used beyond their series) by about 1e-5 relative: 2e-5 of the distance from
          // the eye is a hundredth of a pixel of a 1000-pixel view.
          if (error > 0.05 + 2e-5 * distance) {
            ++far;
            if (far < 4) ADD_FAILURE() << k << " of " << cpu.size() << ": " << error << " m at " << distance;
          }
          if (distance < 20'000.0) worstNear = std::max(worstNear, error);
        }
        EXPECT_EQ(far, 0) << spiralProjectionName(projection) << " correct " << correct
                          << " altitude " << camera.altitudeM;
        EXPECT_LT(worstNear, 0.05);
      }
    }
  }
}

TEST_F(SpiralRendererTest, NoHolesFromOrbitNearTheGroundOrAtTheFan) {
  std::unique_ptr<SpiralRenderer> spiral = makeSpiral();
  ASSERT_TRUE(spiral);
  // Straight down: the fan is at the middle of the image, the spiral round it.
  for (const GeoCamera& camera : {GeoCamera{30.0, 20.0, 20'000'000.0, 0.0, -90.0, 40.0},
                                  GeoCamera{41.5, 11.5, 3000.0, 0.0, -90.0, 60.0},
                                  GeoCamera{41.5, 11.5, 3000.0, 30.0, -12.0, 60.0}}) {
    const ViewSetup view = viewFrom(camera, 200, 150);
    // A few frames for the feedback, each checked.
    for (int frame = 0; frame < 6; ++frame) {
      const test::RenderedFrame drawn = test::renderFrame(*spiral, view);
      EXPECT_EQ(test::groundHoles(drawn, view, 1e9), 0)
          << "altitude " << camera.altitudeM << " frame " << frame;
    }
  }
}

TEST_F(SpiralRendererTest, NearTheGroundTheSpiralDrawsTheStoresSurface) {
  SpiralOptions options;
  options.radiusMode = SpiralRadiusMode::Analytic;
  std::unique_ptr<SpiralRenderer> spiral = makeSpiral(options);
  ASSERT_TRUE(spiral);
  // Straight down from 5 km over the fine area.
  const GeoCamera camera{42.0, 12.0, 5000.0, 0.0, -90.0, 30.0};
  const ViewSetup view = viewFrom(camera, 160, 120);
  const test::RenderedFrame drawn = test::renderFrame(*spiral, view);
  Result<HeightGrid> region = readGlobalRegion(*test::syntheticEarth(), 10, {11.9, 41.9, 12.1, 42.1});
  ASSERT_TRUE(region) << region.error().message;
  Result<GlobeReferenceRenderer> reference = GlobeReferenceRenderer::create(region.value(), nullptr);
  ASSERT_TRUE(reference) << reference.error().message;
  const test::RenderedFrame truth = test::renderFrame(reference.value(), view);
  double sumM = 0.0, worstM = 0.0;
  int compared = 0;
  for (int y = 0; y < view.height; y += 2) {
    for (int x = 0; x < view.width; x += 2) {
      const float a = drawn.depth.at(x, y), b = truth.depth.at(x, y);
      ASSERT_GT(a, 0.0f) << "a hole at " << x << ", " << y;
      if (b <= 0.0f) continue;
      const double d = glm::distance(view.unprojectPixel({x + 0.5, y + 0.5}, a),
                                     view.unprojectPixel({x + 0.5, y + 0.5}, b));
      sumM += d;
      worstM = std::max(worstM, d);
      ++compared;
    }
  }
  ASSERT_GT(compared, 4000);
  // Coarser than every sample (the spiral's triangles cover several), but the same ground:
  // the ripples are 400 m high and 3.3 km long.
  EXPECT_LT(sumM / compared, 30.0);
  EXPECT_LT(worstM, 250.0);
  RecordProperty("mean_m", std::to_string(sumM / compared));
  RecordProperty("worst_m", std::to_string(worstM));
}

TEST_F(SpiralRendererTest, TheFeedbackSettlesOnAStillCameraAndFollowsAZoom) {
  std::unique_ptr<SpiralRenderer> spiral = makeSpiral();
  ASSERT_TRUE(spiral);
  GeoCamera camera{41.5, 11.5, 50'000.0, 0.0, -90.0, 40.0};
  std::vector<double> minRadii;
  for (int frame = 0; frame < 60; ++frame) {
    const ViewSetup view = viewFrom(camera, 160, 120);
    test::renderFrame(*spiral, view);
    minRadii.push_back(spiral->frameInfo().radii.minRad);
  }
  const SpiralFrameInfo& settled = spiral->frameInfo();
  // The fan's pixels within the dead band of the target, and the radius still.
  EXPECT_GT(double(settled.fanPixels), 256.0 / 1.3 - 1.0);
  EXPECT_LT(double(settled.fanPixels), 256.0 * 1.3 + 1.0);
  EXPECT_EQ(minRadii[50], minRadii.back());
  // Near the analytic choice for the same camera (the fan's disc seen straight down).
  EXPECT_NEAR(std::log(settled.radii.minRad / settled.analytic.minRad), 0.0, 0.4);
  // Zooming in 5 % a frame: the radius follows down, each frame's step bounded.
  const double before = settled.radii.minRad;
  for (int frame = 0; frame < 40; ++frame) {
    camera.altitudeM *= 0.95;
    test::renderFrame(*spiral, viewFrom(camera, 160, 120));
  }
  EXPECT_LT(spiral->frameInfo().radii.minRad, 0.35 * before);
}

// A ramp of a step every two texels, wrapping every 512: no wrap within 1.5 km of the middle.
std::uint8_t rampOf(int texel) { return std::uint8_t(((texel + 256) / 2) % 256); }

// A 2048-texel image over 11.9..12.1 E, 41.95..42.15 N (11 m texels), its western quarter masked
// out: red and green ramp with x and y (a texel's colour says where it is). Written into `dir`,
// a folder of the calling test process's own (tests run in parallel; the synthetic Earth takes
// the test's fresh folder).
std::filesystem::path writeRampImage(const std::filesystem::path& dir) {
  const std::filesystem::path path = dir / "ramp.tif";
  test::writeTestImage({2048, 2048, 11.9, 42.15, 0.2 / 2048.0, 4326,
                        [](int x, int y) {
                          return std::array<std::uint8_t, 4>{rampOf(x), rampOf(y), 128,
                                                             std::uint8_t(x < 512 ? 0 : 255)};
                        }},
                       path);
  return path;
}

TEST_F(SpiralRendererTest, ImageryIsDrapedWhereItLiesAtTheDetailTheViewNeeds) {
  SpiralOptions options;
  options.radiusMode = SpiralRadiusMode::Analytic;
  options.imagery = {writeRampImage(test::processFixtureDir("spiral-ramp"))};
  std::unique_ptr<SpiralRenderer> spiral = makeSpiral(options);
  ASSERT_TRUE(spiral);
  ASSERT_NE(spiral->imagery(), nullptr);
  // Straight down from 3 km on the image's middle: 11 m pixels, full detail.
  const GeoCamera camera{42.05, 12.0, 3000.0, 0.0, -90.0, 30.0};
  const ViewSetup view = viewFrom(camera, 200, 150);
  const test::RenderedFrame drawn = test::renderFrame(*spiral, view);
  (void)writePng(drawn.colour, test::testOutputDir() / "spiral-imagery-ramp.png");
  const TextureQuadtree& tree = spiral->imagery()->quadtree(0);
  EXPECT_GT(tree.drawn().size(), 1u);
  bool centreAtFullDetail = false;
  for (const QuadDrawnNode& node : tree.drawn()) {
    const int side = 256 << node.id.level;
    if (node.id.x * side <= 1024 && 1024 < (node.id.x + 1) * side && node.id.y * side <= 1024 &&
        1024 < (node.id.y + 1) * side) {
      centreAtFullDetail = node.mip == 0;
    }
  }
  EXPECT_TRUE(centreAtFullDetail);
  // 0.2 degrees of longitude at 42 N over 2048 texels: 8.05 m east-west (11 m north-south).
  EXPECT_NEAR(spiral->frameInfo().imagery.finestTexelM, 8.05, 0.5);
  // The CPU reference: each pixel's ground point (from its depth) in the image says its colour.
  int compared = 0, worst = 0;
  for (int y = 10; y < view.height; y += 20) {
    for (int x = 10; x < view.width; x += 20) {
      const glm::dvec3 ground = view.unprojectPixel({x + 0.5, y + 0.5}, drawn.depth.at(x, y));
      const wgs84::Geodetic g = wgs84::ecefToGeodetic(ground);
      const double tx = (g.lonRad / wgs84::kDegree - 11.9) / 0.2 * 2048.0;
      const double ty = (42.15 - g.latRad / wgs84::kDegree) / 0.2 * 2048.0;
      const auto colour = drawn.colour.at(x, y);
      worst = std::max({worst, std::abs(int(colour[0]) - int(rampOf(int(tx)))),
                        std::abs(int(colour[1]) - int(rampOf(int(ty)))), std::abs(int(colour[2]) - 128)});
      ++compared;
    }
  }
  EXPECT_EQ(compared, 70);
  // Within a step (two texels, 16 to 22 m: two pixels) of where the image puts the colour.
  EXPECT_LE(worst, 1);
  RecordProperty("worst_steps", std::to_string(worst));
  // Over the masked quarter's edge: the terrain shows where the image is masked out.
  SpiralOptions plain = options;
  plain.imagery.clear();
  std::unique_ptr<SpiralRenderer> terrainOnly = makeSpiral(plain);
  ASSERT_TRUE(terrainOnly);
  const ViewSetup edge = viewFrom({42.05, 11.95, 3000.0, 0.0, -90.0, 30.0}, 200, 150);
  const test::RenderedFrame masked = test::renderFrame(*spiral, edge);
  const test::RenderedFrame bare = test::renderFrame(*terrainOnly, edge);
  (void)writePng(masked.colour, test::testOutputDir() / "spiral-imagery-masked.png");
  for (int c = 0; c < 3; ++c) {
    EXPECT_EQ(int(masked.colour.at(40, 75)[c]), int(bare.colour.at(40, 75)[c]));  // west: masked
  }
  EXPECT_EQ(int(masked.colour.at(160, 75)[2]), 128);  // east: the image (blue 128)
  EXPECT_NE(int(bare.colour.at(160, 75)[2]), 128);
  // Looking away, the tree merges back to its root; nothing drawn is ever without its texture.
  const ViewSetup away = viewFrom({41.5, 12.0, 3000.0, 180.0, -30.0, 30.0}, 200, 150);
  for (int frame = 0; frame < 8; ++frame) test::renderFrame(*spiral, away);
  ASSERT_EQ(tree.drawn().size(), 1u);
  EXPECT_EQ(tree.drawn().front().id, tree.root());
  for (const QuadDrawnNode& node : tree.drawn()) EXPECT_TRUE(tree.isResident({node.id, node.mip}));
}

TEST_F(SpiralRendererTest, ADecalIsDrawnOnTopOfTheImageryBelowIt) {
  // A 64-texel decal (solid orange, a transparent border) over the ramp's middle, in Web
  // Mercator: another CRS, drawn the same way, later images on top.
  const std::filesystem::path dir = test::processFixtureDir("spiral-decal");
  const double lon0 = 11.995, lon1 = 12.005;  // 0.01 degrees: about 830 m
  const double x0 = lon0 * 20037508.342789244 / 180.0, x1 = lon1 * 20037508.342789244 / 180.0;
  const double y = std::log(std::tan(std::numbers::pi / 4.0 + 42.055 * std::numbers::pi / 360.0)) *
                   6378137.0;
  test::writeTestImage({64, 64, x0, y, (x1 - x0) / 64.0, 3857,
                        [](int x, int yy) {
                          const bool border = x < 2 || yy < 2 || x > 61 || yy > 61;
                          return std::array<std::uint8_t, 4>{250, 140, 20, std::uint8_t(border ? 0 : 255)};
                        }},
                       dir / "decal.tif");
  SpiralOptions options;
  options.radiusMode = SpiralRadiusMode::Analytic;
  options.imagery = {writeRampImage(dir), dir / "decal.tif"};
  std::unique_ptr<SpiralRenderer> spiral = makeSpiral(options);
  ASSERT_TRUE(spiral);
  ASSERT_EQ(spiral->imagery()->imageCount(), 2u);
  // 3 km straight down on the decal's north-west quarter: the decal at the middle, the ramp round it.
  const ViewSetup view = viewFrom({42.052, 11.998, 3000.0, 0.0, -90.0, 30.0}, 200, 150);
  const test::RenderedFrame drawn = test::renderFrame(*spiral, view);
  (void)writePng(drawn.colour, test::testOutputDir() / "spiral-imagery-decal.png");
  const auto centre = drawn.colour.at(100, 75);
  EXPECT_EQ(int(centre[0]), 250);
  EXPECT_EQ(int(centre[1]), 140);
  EXPECT_EQ(int(centre[2]), 20);
  const auto corner = drawn.colour.at(5, 5);  // north-west of the decal: the ramp
  EXPECT_EQ(int(corner[2]), 128);
}

}  // namespace
}  // namespace tellus
