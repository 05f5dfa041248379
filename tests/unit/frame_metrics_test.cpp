// Image-space metrics on synthetic frames, against hand calculations.
#include <cmath>
#include <numbers>

#include <gtest/gtest.h>

#include "tellus/eval/depth_truth_error.hpp"
#include "tellus/eval/frame_metrics.hpp"

namespace tellus {
namespace {

HeightGrid flatGrid(float height) {
  HeightGrid grid(401, 401);
  grid.spacingXM = grid.spacingYM = 50.0;  // 20 km square
  std::fill(grid.heights.begin(), grid.heights.end(), height);
  return grid;
}

// The depth image a perfect renderer would produce of the plane z = planeZ.
DepthImage renderPlane(const ViewSetup& view, double planeZ) {
  DepthImage image{view.width, view.height,
                   std::vector<float>(std::size_t(view.width * view.height), 0.0f)};
  for (int y = 0; y < view.height; ++y) {
    for (int x = 0; x < view.width; ++x) {
      // The ray through the pixel centre: two points on it from the unprojection.
      const glm::dvec3 a = view.unprojectPixel({x + 0.5, y + 0.5}, 1.0);
      const glm::dvec3 b = view.unprojectPixel({x + 0.5, y + 0.5}, 0.5);
      const glm::dvec3 dir = b - a;
      if (dir.z >= 0.0) continue;  // above the horizon
      const glm::dvec3 hit = a + dir * ((planeZ - a.z) / dir.z);
      glm::dvec2 pixel;
      double depth = 0.0;
      if (!view.projectToPixel(hit, pixel, &depth) || depth <= 0.0) continue;
      image.depth[std::size_t(y * view.width + x)] = float(depth);
    }
  }
  return image;
}

ViewSetup horizontalView(const HeightGrid& grid) {
  Camera camera;
  camera.position = {10000.0, 500.0, 150.0};
  camera.yawDeg = 0.0;    // north, across the grid
  camera.pitchDeg = 0.0;  // horizontal: a vertical offset moves pixels straight down
  camera.fovYDeg = 60.0;
  return ViewSetup::create(camera, grid.worldBounds(), 160, 120);
}

TEST(FrameMetrics, UnprojectInvertsProject) {
  const HeightGrid grid = flatGrid(100.0f);
  const ViewSetup view = horizontalView(grid);
  const glm::dvec3 point{10300.0, 4000.0, 90.0};
  glm::dvec2 pixel;
  double depth = 0.0;
  ASSERT_TRUE(view.projectToPixel(point, pixel, &depth));
  EXPECT_LT(glm::distance(view.unprojectPixel(pixel, depth), point), 1e-6);
}

TEST(FrameMetrics, AUniformHeightOffsetMatchesAHandCalculation) {
  const HeightGrid truth = flatGrid(100.0f);
  const ViewSetup view = horizontalView(truth);
  const double offset = 5.0;  // the "renderer" drew the plane 5 m too high
  const DepthImage drawn = renderPlane(view, 100.0 + offset);
  const ScreenSpaceError error = measureScreenSpaceError(drawn, view, truth);
  ASSERT_GT(error.summary.pixels, 1000u);
  // Pitch 0: a point at forward distance d moves by offset * f / d pixels, f being the focal
  // length in pixels, (height / 2) / tan(fov / 2).
  const double f = 0.5 * view.height / std::tan(0.5 * 60.0 * std::numbers::pi / 180.0);
  int checked = 0;
  for (int y = 0; y < view.height; ++y) {
    for (int x = 0; x < view.width; ++x) {
      const float d = drawn.at(x, y);
      if (d <= 0.0f) {
        EXPECT_LT(error.errorPx[std::size_t(y * view.width + x)], 0.0f);
        continue;
      }
      const glm::dvec3 p = view.unprojectPixel({x + 0.5, y + 0.5}, d);
      const double forward = glm::dot(p - view.camera.position, view.camera.forward());
      EXPECT_NEAR(error.errorPx[std::size_t(y * view.width + x)], offset * f / forward,
                  1e-3 * (1.0 + offset * f / forward))
          << x << "," << y;
      ++checked;
    }
  }
  EXPECT_GT(checked, 1000);
  // Without the offset the error vanishes (float depth precision: well under a pixel).
  const ScreenSpaceError exact = measureScreenSpaceError(renderPlane(view, 100.0), view, truth);
  EXPECT_LT(exact.summary.maxPx, 0.05);
}

// 3D terrain: the truth is a depth image (depth_truth_error.hpp). Two horizontal planes seen by a
// horizontal camera: each drawn point's nearest true point is the one below it, so the error is
// the flat world's, pixel for pixel, wherever that displacement fits the candidate window; where
// it does not (the foot off the image, or farther than the window reaches) the error falls back
// to the distance along the ray, which is never smaller. Identical images score 0; a pixel drawn
// in one image only is not measured.
TEST(FrameMetrics, DepthTruthErrorOfAPlaneIsTheFlatWorldsError) {
  const HeightGrid grid = flatGrid(100.0f);
  const ViewSetup view = horizontalView(grid);
  const DepthImage truth = renderPlane(view, 100.0);
  const ScreenSpaceError same = measureDepthTruthError(truth, truth, view);
  ASSERT_GT(same.summary.pixels, 1000u);
  EXPECT_EQ(same.summary.maxPx, 0.0);
  for (const double offset : {0.5, 5.0}) {
    DepthImage drawn = renderPlane(view, 100.0 + offset);
    drawn.depth[std::size_t(view.width * (view.height - 1))] = 0.0f;  // a hole in the drawn image
    const ScreenSpaceError error = measureDepthTruthError(drawn, truth, view);
    const ScreenSpaceError flat = measureScreenSpaceError(drawn, view, grid);
    int matched = 0, fellBack = 0;
    for (int y = 0; y < view.height; ++y) {
      for (int x = 0; x < view.width; ++x) {
        const std::size_t i = std::size_t(y * view.width + x);
        const float e = error.errorPx[i];
        if (drawn.at(x, y) <= 0.0f || truth.at(x, y) <= 0.0f) {
          EXPECT_LT(e, 0.0f) << x << "," << y;
          continue;
        }
        const double expected = flat.errorPx[i];
        // The foot lies straight below on screen: measured while it stays on the image and within
        // twice the window (a candidate halfway there reaches it).
        const bool reachable = y + 0.5 + expected < view.height - 1.0 && expected < 2.0 * kDepthTruthWindowPx;
        if (reachable || expected < 1.0) {
          EXPECT_NEAR(e, expected, 0.01 + 0.01 * expected) << "offset " << offset << " at " << x << "," << y;
          ++matched;
        } else {
          EXPECT_GE(e, expected * 0.99) << "offset " << offset << " at " << x << "," << y;
          ++fellBack;
        }
      }
    }
    EXPECT_GT(matched, 1000) << offset;
    if (offset < 1.0) {
      EXPECT_EQ(fellBack, 0);
    }
    // The distance along the ray, the former measure, grows as 1 / sin of the angle below the
    // horizon: near the horizon it overstates the flat world's error many times over.
    const int x = view.width / 2, y = view.height / 2 + 2;
    const glm::dvec2 pixel{x + 0.5, y + 0.5};
    const double along = glm::distance(view.unprojectPixel(pixel, drawn.at(x, y)),
                                       view.unprojectPixel(pixel, truth.at(x, y))) *
                         (0.5 * view.height / std::tan(0.5 * 60.0 * std::numbers::pi / 180.0)) /
                         glm::distance(view.unprojectPixel(pixel, drawn.at(x, y)), view.camera.position);
    EXPECT_GT(along, 10.0 * error.errorPx[std::size_t(y * view.width + x)]) << offset;
  }
  // A different image size cannot be compared: nothing measured.
  DepthImage small{2, 2, std::vector<float>(4, 0.5f)};
  EXPECT_EQ(measureDepthTruthError(small, truth, view).summary.pixels, 0u);
}

// Popping between two renders of one view: identical geometry scores exactly 0; a level of
// detail 5 m higher than the other moves every pixel by what that offset projects to; pixels
// drawn in one render only are not measured.
TEST(FrameMetrics, PoppingIsTheProjectedDisplacementBetweenTwoLevelsOfDetail) {
  const HeightGrid truth = flatGrid(100.0f);
  const ViewSetup view = horizontalView(truth);
  const DepthImage exact = renderPlane(view, 100.0);
  const ScreenSpaceError same = measurePopping(exact, exact, view, truth);
  ASSERT_GT(same.summary.pixels, 1000u);
  EXPECT_EQ(same.summary.maxPx, 0.0);

  const double offset = 5.0;
  DepthImage raised = renderPlane(view, 100.0 + offset);
  const ScreenSpaceError pop = measurePopping(exact, raised, view, truth);
  const double f = 0.5 * view.height / std::tan(0.5 * 60.0 * std::numbers::pi / 180.0);
  int checked = 0;
  for (int y = 0; y < view.height; ++y) {
    for (int x = 0; x < view.width; ++x) {
      const float d = raised.at(x, y);
      const float value = pop.errorPx[std::size_t(y * view.width + x)];
      if (d <= 0.0f || exact.at(x, y) <= 0.0f) {
        EXPECT_LT(value, 0.0f);
        continue;
      }
      const glm::dvec3 p = view.unprojectPixel({x + 0.5, y + 0.5}, d);
      const double forward = glm::dot(p - view.camera.position, view.camera.forward());
      EXPECT_NEAR(value, offset * f / forward, 0.05 + 1e-3 * offset * f / forward) << x << "," << y;
      ++checked;
    }
  }
  EXPECT_GT(checked, 1000);
  // It is symmetric, and a frame drawn in one render only is not measured at all.
  EXPECT_NEAR(measurePopping(raised, exact, view, truth).summary.p99Px, pop.summary.p99Px, 0.05);
  std::fill(raised.depth.begin(), raised.depth.end(), 0.0f);
  EXPECT_EQ(measurePopping(exact, raised, view, truth).summary.pixels, 0u);
}

TEST(FrameMetrics, SummaryStatistics) {
  std::vector<float> values;
  for (int i = 0; i < 100; ++i) values.push_back(float(i));
  values.push_back(-1.0f);  // no terrain: ignored
  const ErrorSummary s = summariseErrors(values);
  EXPECT_EQ(s.pixels, 100u);
  EXPECT_DOUBLE_EQ(s.meanPx, 49.5);
  EXPECT_DOUBLE_EQ(s.p95Px, 95.0);
  EXPECT_DOUBLE_EQ(s.p99Px, 99.0);
  EXPECT_DOUBLE_EQ(s.maxPx, 99.0);
  EXPECT_EQ(summariseErrors({-1.0f}).pixels, 0u);
}

TEST(FrameMetrics, CracksCountOnlyInsideTheReferenceTerrain) {
  const int w = 20, h = 10;
  const std::uint8_t sentinel[3] = {255, 0, 255};
  std::vector<std::uint8_t> coverage(std::size_t(w * h), 0);
  for (int y = 3; y < h; ++y)
    for (int x = 0; x < w; ++x) coverage[std::size_t(y * w + x)] = 1;  // terrain below row 3
  RgbImage image(w, h);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      std::uint8_t* p = image.at(x, y);
      if (y < 3)
        std::copy(sentinel, sentinel + 3, p);  // sky: sentinel, not a crack
      else
        p[1] = 200;
    }
  std::copy(sentinel, sentinel + 3, image.at(5, 6));   // a hole inside: a crack
  std::copy(sentinel, sentinel + 3, image.at(9, 6));   // another
  std::copy(sentinel, sentinel + 3, image.at(12, 3));  // on the horizon edge: not interior
  image.at(7, 7)[0] = 254;                             // near-sentinel is not sentinel
  const CrackReport report = detectCracks(image, sentinel, coverage);
  EXPECT_EQ(report.crackPixels, 2u);
  EXPECT_EQ(report.mask[std::size_t(6 * w + 5)], 1);
  EXPECT_EQ(report.mask[std::size_t(3 * w + 12)], 0);
  const RgbImage marked = markCracks(image, report);
  EXPECT_EQ(marked.at(7, 6)[0], 255);  // the ring around (5, 6)
}

// A dip of the silhouette (sky reaching down into the reference's terrain from above) is not a
// crack; the same pixels closed off by terrain are.
TEST(FrameMetrics, ALoweredSilhouetteIsNotACrack) {
  const int w = 20, h = 12;
  const std::uint8_t sentinel[3] = {255, 0, 255};
  std::vector<std::uint8_t> coverage(std::size_t(w * h), 0);
  for (int y = 3; y < h; ++y)
    for (int x = 0; x < w; ++x) coverage[std::size_t(y * w + x)] = 1;
  RgbImage image(w, h);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      if (y < 3)
        std::copy(sentinel, sentinel + 3, image.at(x, y));
      else
        image.at(x, y)[1] = 200;
    }
  // A notch 3 px wide from the sky down to row 7.
  for (int y = 3; y <= 7; ++y)
    for (int x = 8; x <= 10; ++x) std::copy(sentinel, sentinel + 3, image.at(x, y));
  CrackReport report = detectCracks(image, sentinel, coverage);
  EXPECT_EQ(report.crackPixels, 0u);
  EXPECT_EQ(report.silhouettePixels, 12u);  // rows 4..7 (row 3 is not interior)
  // Close the notch at row 4: rows 5..7 become a hole.
  for (int x = 8; x <= 10; ++x) image.at(x, 4)[0] = 0, image.at(x, 4)[1] = 200;
  report = detectCracks(image, sentinel, coverage);
  EXPECT_EQ(report.crackPixels, 9u);
}

// Closed solids: an enclosed background pixel whose view ray crossed no back face (open air
// between simplified features) moves to the silhouette count; one that entered the solid stays
// a crack.
TEST(FrameMetrics, EnclosedBackgroundSeenThroughOpenAirIsNotACrack) {
  const int w = 12, h = 10;
  const std::uint8_t sentinel[3] = {255, 0, 255};
  const std::vector<std::uint8_t> coverage(std::size_t(w * h), 1);
  RgbImage image(w, h);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) image.at(x, y)[1] = 200;
  std::copy(sentinel, sentinel + 3, image.at(3, 4));  // through a hole in the surface
  std::copy(sentinel, sentinel + 3, image.at(7, 5));  // between two rock filaments
  std::copy(sentinel, sentinel + 3, image.at(8, 5));
  CrackReport report = detectCracks(image, sentinel, coverage);
  ASSERT_EQ(report.crackPixels, 3u);
  std::vector<std::uint8_t> backFaces(std::size_t(w * h), 0);
  backFaces[std::size_t(4 * w + 3)] = 1;  // the ray through the hole leaves the solid
  excludeOpenAirGaps(report, backFaces);
  EXPECT_EQ(report.crackPixels, 1u);
  EXPECT_EQ(report.silhouettePixels, 2u);
  EXPECT_EQ(report.mask[std::size_t(4 * w + 3)], 1);
  EXPECT_EQ(report.mask[std::size_t(5 * w + 7)], 0);
}

TEST(FrameMetrics, ErrorImageRunsFromGreenToRed) {
  ScreenSpaceError error;
  error.errorPx = {0.0f, 5.0f, 10.0f, 50.0f, -1.0f};
  RgbImage background(5, 1);
  background.at(4, 0)[2] = 77;
  const RgbImage image = errorImage(error, 5, 1, background);
  EXPECT_EQ(std::vector<int>(image.at(0, 0), image.at(0, 0) + 3), (std::vector<int>{0, 255, 0}));
  EXPECT_EQ(std::vector<int>(image.at(1, 0), image.at(1, 0) + 3), (std::vector<int>{255, 255, 0}));
  EXPECT_EQ(std::vector<int>(image.at(2, 0), image.at(2, 0) + 3), (std::vector<int>{255, 0, 0}));
  EXPECT_EQ(std::vector<int>(image.at(3, 0), image.at(3, 0) + 3), (std::vector<int>{255, 0, 0}));
  EXPECT_EQ(image.at(4, 0)[2], 77);  // sky keeps the background
}

}  // namespace
}  // namespace tellus

#include "tellus/eval/path_benchmark.hpp"

namespace tellus {
namespace {

TEST(PathStatistics, DistributionsAndThePooledHistogram) {
  const Distribution d = distributionOf({5.0, 1.0, 3.0, 2.0, 4.0});
  EXPECT_DOUBLE_EQ(d.median, 3.0);
  EXPECT_DOUBLE_EQ(d.min, 1.0);
  EXPECT_DOUBLE_EQ(d.max, 5.0);
  EXPECT_DOUBLE_EQ(d.mean, 3.0);
  EXPECT_NEAR(d.p95, 4.8, 1e-12);  // linear interpolation between ranks
  ErrorHistogram h;
  for (int i = 0; i < 1000; ++i) h.add(float(i) * 0.01f);  // 0 .. 9.99 px
  h.add(-1.0f);                                            // no terrain: ignored
  h.add(100.0f);                                           // overflow bin
  EXPECT_EQ(h.total, 1001u);
  EXPECT_NEAR(h.percentile(0.5), 5.01, 0.011);
  EXPECT_NEAR(h.percentile(0.95), 9.51, 0.011);
  EXPECT_DOUBLE_EQ(h.percentile(1.0), 100.0);
  EXPECT_DOUBLE_EQ(h.max, 100.0);
  // Percentiles never exceed the largest value: all zeros (no popping at all) give exactly 0.
  ErrorHistogram zeros;
  for (int i = 0; i < 10; ++i) zeros.add(0.0f);
  EXPECT_DOUBLE_EQ(zeros.percentile(0.99), 0.0);
  ErrorHistogram small;
  small.add(0.004f);
  EXPECT_FLOAT_EQ(float(small.percentile(0.99)), 0.004f);
}

}  // namespace
}  // namespace tellus

namespace tellus {
namespace {

TEST(HeightGridMesh, FollowsTheReferenceRenderersTriangles) {
  HeightGrid grid(2, 2);
  grid.spacingXM = grid.spacingYM = 10.0;
  // Row 0 is north: (0,0) NW = 0, (1,0) NE = 10, (0,1) SW = 20, (1,1) SE = 100.
  grid.at(0, 0) = 0.0f;
  grid.at(1, 0) = 10.0f;
  grid.at(0, 1) = 20.0f;
  grid.at(1, 1) = 100.0f;
  // World y grows north: the SW sample is at (0, 0), the NE one at (10, 10).
  EXPECT_DOUBLE_EQ(grid.meshHeightAtWorld(0.0, 0.0), 20.0);    // SW corner
  EXPECT_DOUBLE_EQ(grid.meshHeightAtWorld(10.0, 10.0), 10.0);  // NE corner
  EXPECT_DOUBLE_EQ(grid.meshHeightAtWorld(5.0, 5.0), 15.0);    // on the NE-SW diagonal
  EXPECT_DOUBLE_EQ(grid.meshHeightAtWorld(2.5, 7.5), 10.0 * 0.25 + 20.0 * 0.25);  // NW triangle
  EXPECT_NEAR(grid.meshHeightAtWorld(7.5, 2.5), 100.0 * 0.5 + 20.0 * 0.25 + 10.0 * 0.25, 1e-9);
  EXPECT_NEAR(grid.heightAtWorld(5.0, 5.0), 32.5, 1e-5);  // bilinear differs from the mesh
}

}  // namespace
}  // namespace tellus
