// The reference renderer against hand calculations and the CPU twin of the shading:
// flat and sloped planes, where a height step lands in the image, chunk seams, determinism.
#include <cmath>
#include <functional>

#include <gtest/gtest.h>

#include <glm/glm.hpp>

#include "support/gl_test.hpp"
#include "support/test_support.hpp"
#include "tellus/render/output/named_views.hpp"
#include "tellus/render/output/snapshot.hpp"

namespace tellus {
namespace {

using ReferenceRendererTest = test::GlTest;

HeightGrid makeGrid(int w, int h, double spacing, const std::function<float(int, int)>& height) {
  HeightGrid grid(w, h);
  grid.spacingXM = grid.spacingYM = spacing;
  for (int row = 0; row < h; ++row) {
    for (int col = 0; col < w; ++col) grid.at(col, row) = height(col, row);
  }
  return grid;
}

SnapshotOptions smallImage(int w = 160, int h = 120) {
  SnapshotOptions options;
  options.width = w;
  options.height = h;
  options.settings.shading.hazeDensity = 1e-12f;  // effectively no haze: colours are exact
  return options;
}

Camera lookingDownAt(const HeightGrid& grid, double heightAbove) {
  const Aabb b = grid.worldBounds();
  Camera camera;
  camera.position = {b.centre().x, b.centre().y, b.max.z + heightAbove};
  camera.pitchDeg = -90.0;
  camera.fovYDeg = 30.0;
  return camera;
}

glm::ivec3 pixel(const RgbImage& image, int x, int y) {
  const std::uint8_t* p = image.at(x, y);
  return {p[0], p[1], p[2]};
}

glm::ivec3 expectedColour(const ShadingParams& params, float height, glm::vec3 normal) {
  return glm::ivec3(
      glm::round(shadeTerrain(params, height, glm::normalize(normal), {0, 0, 0}) * 255.0f));
}

void expectColourNear(glm::ivec3 actual, glm::ivec3 expected, int tolerance, const char* what) {
  for (int c = 0; c < 3; ++c) {
    EXPECT_NEAR(actual[c], expected[c], tolerance)
        << what << ": got (" << actual.r << "," << actual.g << "," << actual.b << "), expected ("
        << expected.r << "," << expected.g << "," << expected.b << ")";
  }
}

Result<RgbImage> render(const HeightGrid& grid, const Camera& camera,
                        const SnapshotOptions& options) {
  Result<ReferenceRenderer> renderer = ReferenceRenderer::create(grid);
  if (!renderer) return renderer.error();
  return renderSnapshot(renderer.value(), grid, camera, options);
}

TEST_F(ReferenceRendererTest, FlatPlaneRendersTheExpectedColour) {
  const HeightGrid grid = makeGrid(64, 64, 10.0, [](int, int) { return 250.0f; });
  const SnapshotOptions options = smallImage();
  Result<RgbImage> image = render(grid, lookingDownAt(grid, 750.0), options);
  ASSERT_TRUE(image) << image.error().message;
  const glm::ivec3 expected = expectedColour(options.settings.shading, 250.0f, {0, 0, 1});
  for (const glm::ivec2 at :
       {glm::ivec2(80, 60), glm::ivec2(5, 5), glm::ivec2(150, 110), glm::ivec2(20, 100)}) {
    expectColourNear(pixel(*image, at.x, at.y), expected, 2, "flat plane");
  }
}

TEST_F(ReferenceRendererTest, SlopedPlaneIsLitAsTheCpuTwinPredicts) {
  // z = 0.5 x: the normal is (-0.5, 0, 1) normalised, computed by the shader from the heights.
  const HeightGrid grid =
      makeGrid(64, 64, 10.0, [](int col, int) { return 500.0f + 5.0f * float(col); });
  const SnapshotOptions options = smallImage();
  const Camera camera = lookingDownAt(grid, 900.0);
  Result<RgbImage> image = render(grid, camera, options);
  ASSERT_TRUE(image) << image.error().message;
  // The image centre sees the terrain point straight below the camera.
  const float heightBelow = grid.heightAtWorld(camera.position.x, camera.position.y);
  const glm::ivec3 expected =
      expectedColour(options.settings.shading, heightBelow, {-0.5f, 0.0f, 1.0f});
  expectColourNear(pixel(*image, 80, 60), expected, 3, "sloped plane");
  const glm::ivec3 flat = expectedColour(options.settings.shading, heightBelow, {0, 0, 1});
  EXPECT_GT(glm::length(glm::vec3(expected - flat)), 5.0f) << "the test must tell slopes apart";
}

TEST_F(ReferenceRendererTest, AHeightStepLandsWhereTheCameraProjectsIt) {
  // West part at sea level (water colour), east part at 400 m (land colour); the grid (8 km)
  // reaches beyond the view on every side.
  const HeightGrid grid =
      makeGrid(401, 401, 20.0, [](int col, int) { return col <= 200 ? 0.0f : 400.0f; });
  const SnapshotOptions options = smallImage(200, 150);
  Camera camera;
  camera.position = {3800.0, 1500.0, 2500.0};
  camera.yawDeg = 10.0;
  camera.pitchDeg = -60.0;
  camera.fovYDeg = 50.0;
  Result<RgbImage> image = render(grid, camera, options);
  ASSERT_TRUE(image) << image.error().message;
  const ViewSetup view = ViewSetup::create(camera, drawnBounds(grid, 1.0f), 200, 150);
  // The step runs from (x = 4000 m, z = 0) to (x = 4020 m, z = 400); look along the image row
  // where its top edge at y = 3000 m appears.
  glm::dvec2 lowEdge, highEdge;
  ASSERT_TRUE(view.projectToPixel({4000.0, 3000.0, 0.0}, lowEdge));
  ASSERT_TRUE(view.projectToPixel({4020.0, 3000.0, 400.0}, highEdge));
  const int row = int(std::round(highEdge.y));
  ASSERT_GT(row, 5);
  ASSERT_LT(row, 145);
  const auto isWater = [&](int x) {
    const glm::ivec3 p = pixel(*image, x, row);
    return p.b > p.g && p.b > p.r;
  };
  const int left = int(std::floor(std::min(lowEdge.x, highEdge.x))) - 3;
  const int right = int(std::ceil(std::max(highEdge.x, lowEdge.x))) + 3;
  for (int x = 2; x < left && x < 200; ++x) EXPECT_TRUE(isWater(x)) << "x=" << x << " row=" << row;
  for (int x = std::max(right, 0); x < 198; ++x)
    EXPECT_FALSE(isWater(x)) << "x=" << x << " row=" << row;
}

TEST_F(ReferenceRendererTest, ChunkSeamsLeaveNoGaps) {
  // 600 x 300 samples: 3 x 2 chunks, the last ones partial. Seen from above, every pixel must be
  // terrain: a single sky pixel would be a crack between chunks.
  const HeightGrid grid = makeGrid(600, 300, 1.0, [](int col, int row) {
    return 100.0f + 20.0f * std::sin(float(col) * 0.05f) * std::cos(float(row) * 0.07f);
  });
  SnapshotOptions options = smallImage(320, 160);
  options.samples = 1;
  Camera camera;
  camera.position = {299.5, 149.5, 500.0};
  camera.pitchDeg = -90.0;
  camera.fovYDeg = 25.0;  // sees ~220 x 110 m around the centre, across the chunk corners
  Result<RgbImage> image = render(grid, camera, options);
  ASSERT_TRUE(image) << image.error().message;
  const glm::u8vec3 sky = skyColour8(options.settings.shading);
  int skyPixels = 0;
  for (int y = 0; y < image->height; ++y) {
    for (int x = 0; x < image->width; ++x) skyPixels += pixel(*image, x, y) == glm::ivec3(sky);
  }
  EXPECT_EQ(skyPixels, 0);
}

TEST_F(ReferenceRendererTest, RenderingIsDeterministicAndWireframeShowsEdges) {
  const HeightGrid grid = makeGrid(129, 129, 30.0, [](int col, int row) {
    return 300.0f + 200.0f * std::sin(float(col) * 0.1f) + 150.0f * std::cos(float(row) * 0.13f);
  });
  Result<ReferenceRenderer> renderer = ReferenceRenderer::create(grid);
  ASSERT_TRUE(renderer) << renderer.error().message;
  SnapshotOptions options = smallImage(200, 150);
  const Camera camera = namedView("oblique", grid, 200.0 / 150.0).value();
  FrameStats stats;
  Result<RgbImage> first = renderSnapshot(*renderer, grid, camera, options, &stats);
  Result<RgbImage> second = renderSnapshot(*renderer, grid, camera, options);
  ASSERT_TRUE(first && second);
  EXPECT_EQ(first->pixels, second->pixels);
  EXPECT_EQ(stats.triangles, 128u * 128u * 2u);
  EXPECT_EQ(stats.drawCalls, 1u);

  options.settings.wireframe = true;
  Result<RgbImage> wire = renderSnapshot(*renderer, grid, camera, options);
  ASSERT_TRUE(wire);
  double plain = 0.0, lined = 0.0;
  for (size_t i = 0; i < first->pixels.size(); ++i) {
    plain += first->pixels[i];
    lined += wire->pixels[i];
  }
  EXPECT_LT(lined, plain * 0.97) << "dark edges must darken the image";
}

}  // namespace
}  // namespace tellus
