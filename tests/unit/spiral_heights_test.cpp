// The spiral globe's height windows and projections (seed 001), GL-free: a window holds the
// store's surface of its depth sample for sample (checked against storeSampleSource, the store's
// one rule), across the antimeridian and at the poles; the whole-world base wraps; a vertex
// takes the depth that resolves the spiral there, or a coarser window holding it; the
// projections put a vertex where double-precision geodesy does, to millimetres near the focal
// point; the analytic radii and the occlusion feedback behave.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <map>
#include <stdexcept>

#include <glm/geometric.hpp>

#include "support/terrain_fixtures.hpp"
#include "support/test_support.hpp"
#include "tellus/core/geodesy.hpp"
#include "tellus/lod/spiral/spiral_height_levels.hpp"
#include "tellus/lod/spiral/spiral_projection.hpp"
#include "tellus/lod/spiral/spiral_radius.hpp"
#include "tellus/tiles/global_store_builder.hpp"

namespace tellus {
namespace {

const GlobalStore& sparseStore() { return test::sparseGlobalStore(); }

// The store's surface at sample (i, j) of `depth` (columns wrapped, rows clamped) by
// storeSampleSource, independently of readSpiralHeightWindow.
double surfaceSample(const GlobalStore& store, int depth, std::int64_t i, std::int64_t j) {
  const int n = store.tileCells();
  const std::int64_t total = std::int64_t(GlobalTiling::tilesX(depth)) * n;
  const std::int64_t rows = std::int64_t(GlobalTiling::tilesY(depth)) * n;
  i = ((i % total) + total) % total;
  j = std::clamp<std::int64_t>(j, 0, rows);
  const GeoTileKey key{depth, int(std::min(i / n, total / n - 1)), int(std::min(j / n, rows / n - 1))};
  const StoreSampleSource source =
      storeSampleSource(store, key, int(i - std::int64_t(key.x) * n), int(j - std::int64_t(key.y) * n));
  static std::map<GeoTileKey, std::vector<float>> tiles;
  auto it = tiles.find(source.source);
  if (it == tiles.end()) {
    std::vector<float> heights(store.tileShape().sampleCount());
    EXPECT_TRUE(store.readTileMetres(source.source, heights));
    it = tiles.emplace(source.source, std::move(heights)).first;
  }
  return tileSurfaceAt(it->second, n, source.u, source.v);
}

void expectWindowIsTheSurface(const GlobalStore& store, const SpiralHeightWindow& window) {
  int checked = 0;
  for (int y = 0; y < window.rows; y += 3) {
    for (int x = 0; x < window.columns; x += 3) {
      const double expected = surfaceSample(store, window.depth, window.column0 + x, window.row0 + y);
      ASSERT_NEAR(window.heights[std::size_t(y) * window.columns + x], expected, 1e-3)
          << "depth " << window.depth << " sample " << x << ", " << y;
      ++checked;
    }
  }
  EXPECT_GT(checked, 100);
}

TEST(SpiralHeights, WindowsHoldTheStoreSurfaceAcrossTheAntimeridianAndPoles) {
  const GlobalStore& store = sparseStore();
  const int n = store.tileCells();
  // Over the fine area (depth 7 stored), across the antimeridian, over a pole.
  for (const auto& [depth, lat, lon] : {std::tuple{7, 41.0, 11.0}, std::tuple{6, 40.5, 11.7},
                                        std::tuple{5, -20.0, 179.9}, std::tuple{4, 88.0, -30.0}}) {
    SpiralHeightWindow window = spiralWindowAround(depth, n, 65, lat, lon);
    ASSERT_TRUE(readSpiralHeightWindow(store, nullptr, window));
    expectWindowIsTheSurface(store, window);
    // The focal point sits at the window's centre sample.
    const glm::dvec2 at = window.samplePosition(lat, lon);
    EXPECT_NEAR(at.x, 32.0, 0.5);
    EXPECT_NEAR(at.y, 32.0, 0.5);
    EXPECT_FALSE(spiralWindowNeedsMove(window, lat, lon));
    const double step = GlobalTiling::tileSizeDeg(depth) / n;
    EXPECT_FALSE(spiralWindowNeedsMove(window, lat, lon + 7.0 * step));
    EXPECT_TRUE(spiralWindowNeedsMove(window, lat, lon + 9.0 * step));
  }
  // The base wraps round the world: its last column is its first.
  SpiralHeightWindow base = spiralWholeWorld(spiralBaseDepth(n), n);
  EXPECT_LE(base.columns - 1, kSpiralBaseColumns);
  ASSERT_TRUE(readSpiralHeightWindow(store, nullptr, base));
  expectWindowIsTheSurface(store, base);
  for (int y = 0; y < base.rows; y += 7) {
    EXPECT_EQ(base.heights[std::size_t(y) * base.columns],
              base.heights[std::size_t(y) * base.columns + base.columns - 1]);
  }
  EXPECT_FLOAT_EQ(spiralWindowHeight(base, 0.25f, 10.0f),
                  spiralWindowHeight(base, float(base.columns - 1) + 0.25f, 10.0f));
}

// The height windows round (lat, lon) of every depth from the base's to `deepest` (`missing`:
// a depth whose window is left out of the stack), and the stack over them. Not copyable: the
// stack points into it.
struct WindowStack {
  SpiralHeightWindow base;
  std::vector<SpiralHeightWindow> windows;
  SpiralHeightStack stack;
  WindowStack(const WindowStack&) = delete;
  WindowStack(const GlobalStore& store, double lat, double lon, int deepest, int missing = -1) {
    const int n = store.tileCells();
    base = spiralWholeWorld(spiralBaseDepth(n), n);
    EXPECT_TRUE(readSpiralHeightWindow(store, nullptr, base));
    for (int depth = base.depth + 1; depth <= deepest; ++depth) {
      windows.push_back(spiralWindowAround(depth, n, 65, lat, lon));
      EXPECT_TRUE(readSpiralHeightWindow(store, nullptr, windows.back()));
    }
    stack.base = &base;
    stack.baseFocal = glm::vec2(base.samplePosition(lat, lon));
    for (const SpiralHeightWindow& w : windows) {
      stack.levels.push_back(w.depth == missing ? nullptr : &w);
      stack.levelFocal.push_back(glm::vec2(w.samplePosition(lat, lon)));
    }
  }
};

TEST(SpiralHeights, AVertexTakesTheDepthThatResolvesItsSpacingOrACoarserWindow) {
  const GlobalStore& store = sparseStore();
  const int n = store.tileCells();
  const int baseDepth = spiralBaseDepth(n);
  // The sample spacing of the chosen depth is at most the spacing asked for, and more than half.
  for (float spacing : {1e-2f, 3e-3f, 1e-3f, 2e-4f}) {
    const int depth = spiralLevelDepthFor(spacing, n, 0, 20);
    const double step = M_PI / double(1 << depth) / n;
    EXPECT_LE(step, spacing * 1.0001);
    EXPECT_GT(step, spacing * 0.4999);
  }
  EXPECT_EQ(spiralLevelDepthFor(1e-9f, n, baseDepth, 6), 6);
  EXPECT_EQ(spiralLevelDepthFor(1.0f, n, baseDepth, 6), baseDepth);

  // A stack round (41, 11): windows at every depth up to 7, the depth-5 one missing.
  const double lat = 41.0, lon = 11.0;
  const WindowStack windowStack(store, lat, lon, 7, /*missing=*/5);
  const SpiralHeightStack& stack = windowStack.stack;
  const SpiralHeightWindow& base = windowStack.base;
  const std::vector<SpiralHeightWindow>& windows = windowStack.windows;
  const SpiralFocus focus = makeSpiralFocus(lat * wgs84::kDegree, lon * wgs84::kDegree);
  const float perRevolution = 60.0f;
  for (float radius : {1e-5f, 1e-4f, 1e-3f, 3e-3f, 1e-2f, 0.3f}) {
    const glm::vec2 direction(0.6f, 0.8f);
    const glm::vec2 offset = spiralLatLonOffset(direction, radius, focus);
    const SpiralHeightLookup h =
        spiralLookupHeight(stack, offset, radius, perRevolution, /*blendDepths=*/false);
    const int wanted = spiralLevelDepthFor(radius * 6.2831853f / perRevolution, n, baseDepth, 7);
    // The wanted depth if its window holds the vertex, else coarser; never the missing one.
    EXPECT_LE(h.depth, wanted) << radius;
    EXPECT_NE(h.depth, 5) << radius;
    if (wanted != 5 && radius <= 1e-3f) {
      EXPECT_EQ(h.depth, wanted) << radius;
    }
    // The height is the store's surface there (it nests: any depth's samples lie on finer ones).
    const double vLat = lat + offset.x / wgs84::kDegree, vLon = lon + offset.y / wgs84::kDegree;
    const SpiralHeightWindow& from =
        h.depth == baseDepth ? base : windows[std::size_t(h.depth - baseDepth - 1)];
    const glm::dvec2 at = from.samplePosition(vLat, vLon);
    EXPECT_NEAR(h.heightM, spiralWindowHeight(from, float(at.x), float(at.y)), 0.05) << radius;
  }
}

// Blended, a vertex's height does not jump where its spacing crosses from one depth to the next:
// just finer than the crossing it is (almost all) the coarser depth's, as just coarser. Stepped,
// it switches surfaces there.
// A store with hills of 5 km and 300 m in a fine area (0.005 degrees, 16-cell tiles: depths to
// 11), so that neighbouring depths' surfaces differ by metres.
double roughRelief(double latDeg, double lonDeg) {
  return 800.0 + 300.0 * std::sin(7200.0 * latDeg * 0.01745) * std::sin(6100.0 * lonDeg * 0.01745);
}

const GlobalStore& roughStore() {
  static const std::shared_ptr<GlobalStore> store = [] {
    const std::filesystem::path dir = test::freshTestDir();
    const std::filesystem::path coarse =
        test::writeLatLonTerrain(dir / "coarse.tif", -180.0, 90.0, 1.0, 360, 181, roughRelief);
    const std::filesystem::path fine =
        test::writeLatLonTerrain(dir / "fine.tif", 10.0, 42.0, 0.005, 401, 401, roughRelief);
    GlobalBuildOptions options;
    options.tileCells = 16;
    EXPECT_TRUE(buildGlobalStore({coarse, fine}, dir / "rough.tstore", options));
    Result<std::shared_ptr<GlobalStore>> opened = GlobalStore::open(dir / "rough.tstore");
    EXPECT_TRUE(opened);
    return opened ? opened.value() : nullptr;
  }();
  if (!store) throw std::runtime_error("the rough global store could not be built");
  return *store;
}

TEST(SpiralHeights, ABlendedVertexCrossesADepthWithoutAStep) {
  const GlobalStore& store = roughStore();
  const int n = store.tileCells();
  const int baseDepth = spiralBaseDepth(n);
  const double lat = 41.0, lon = 11.0;
  const WindowStack windowStack(store, lat, lon, 11);
  const SpiralHeightStack& stack = windowStack.stack;
  const SpiralFocus focus = makeSpiralFocus(lat * wgs84::kDegree, lon * wgs84::kDegree);
  const float perRevolution = 60.0f;
  double worstBlended = 0.0, worstStepped = 0.0;
  for (int depth = baseDepth + 1; depth <= 10; ++depth) {
    // The radius whose spacing is depth's sample spacing: the crossing between depth and depth + 1.
    const double crossing = M_PI / double(1 << depth) / n * perRevolution / (2.0 * M_PI);
    const glm::vec2 direction(0.6f, 0.8f);
    const auto heightAt = [&](double radius, bool blend) {
      const glm::vec2 offset = spiralLatLonOffset(direction, float(radius), focus);
      return spiralLookupHeight(stack, offset, float(radius), perRevolution, blend);
    };
    const SpiralHeightLookup finer = heightAt(crossing * (1.0 - 1e-4), true);
    const SpiralHeightLookup coarser = heightAt(crossing * (1.0 + 1e-4), true);
    EXPECT_EQ(finer.depth, depth + 1);
    EXPECT_EQ(finer.coarserDepth, depth);
    EXPECT_GT(finer.coarserShare, 0.99f);
    EXPECT_EQ(coarser.depth, depth);
    EXPECT_LT(coarser.coarserShare, 0.01f);
    worstBlended = std::max(worstBlended, double(std::abs(finer.heightM - coarser.heightM)));
    worstStepped = std::max(worstStepped, double(std::abs(heightAt(crossing * (1.0 - 1e-4), false).heightM -
                                                          heightAt(crossing * (1.0 + 1e-4), false).heightM)));
  }
  std::printf("a vertex crossing a depth moves %.4f m blended, %.4f m stepped\n", worstBlended,
              worstStepped);
  ASSERT_GT(worstStepped, 1.0);  // the depths' surfaces do differ there
  EXPECT_LT(worstBlended, 0.02 * worstStepped);
}

TEST(SpiralProjection, GlobeOffsetsMatchDoubleGeodesyToMillimetres) {
  for (const auto& [latDeg, lonDeg] : {std::pair{35.36, 138.73}, std::pair{-89.9, 10.0},
                                       std::pair{0.0, 179.99}, std::pair{67.5, -20.0}}) {
    const SpiralFocus focus = makeSpiralFocus(latDeg * wgs84::kDegree, lonDeg * wgs84::kDegree);
    const glm::dvec3 focal = wgs84::geodeticToEcef({latDeg * wgs84::kDegree, lonDeg * wgs84::kDegree, 0.0});
    for (float radius : {0.0f, 2e-7f, 3e-6f, 1e-4f, 2e-3f, 0.05f, 0.4f, 1.5f}) {
      for (float azimuth : {0.0f, 1.0f, 2.5f, 4.0f, 5.9f}) {
        const glm::vec2 direction(std::sin(azimuth), std::cos(azimuth));
        const float height = 3776.0f;
        const glm::vec2 offset = spiralLatLonOffset(direction, radius, focus);
        // The point in double: the normal's latitude and longitude, then the ellipsoid.
        const double lat = latDeg * wgs84::kDegree + double(offset.x);
        const double lon = lonDeg * wgs84::kDegree + double(offset.y);
        const glm::dvec3 expected = wgs84::geodeticToEcef({lat, lon, double(height)}) - focal;
        const glm::dvec3 got(spiralGlobeOffset(direction, radius, height, focus));
        // Float offsets: relative 2e-7 of the distance, and a millimetre near the focal point.
        const double tolerance = 1e-3 + 4e-7 * glm::length(expected);
        EXPECT_NEAR(glm::length(got - expected), 0.0, tolerance)
            << latDeg << "," << lonDeg << " r " << radius << " az " << azimuth;
        // The normal is the ellipsoid's there, and lies at angle r from the focal point's.
        const glm::dvec3 normal(spiralNormal(direction, radius, focus));
        EXPECT_NEAR(glm::length(normal), 1.0, 1e-6);
        EXPECT_NEAR(std::acos(std::clamp(glm::dot(normal, glm::dvec3(focus.up)), -1.0, 1.0)),
                    double(radius), 1e-3 + 1e-6 * radius);
      }
    }
  }
  // Across the pole: 0.2 rad north of 89.9 N lands on the far meridian.
  const SpiralFocus polar = makeSpiralFocus(89.9 * wgs84::kDegree, 10.0 * wgs84::kDegree);
  const glm::vec2 over = spiralLatLonOffset({0.0f, 1.0f}, 0.2f, polar);
  EXPECT_NEAR(std::abs(over.y), M_PI, 1e-5);
  EXPECT_NEAR(89.9 * wgs84::kDegree + over.x, M_PI / 2 - (0.2 - 0.1 * wgs84::kDegree), 1e-5);
}

TEST(SpiralProjection, ModesAgreeWithTheGlobeAtTheFocalPointAndDivergeAway) {
  const SpiralFocus focus = makeSpiralFocus(35.0 * wgs84::kDegree, 138.0 * wgs84::kDegree);
  const glm::vec2 direction(0.6f, 0.8f);
  for (SpiralProjection p : {SpiralProjection::Flat, SpiralProjection::Hyperbolic,
                             SpiralProjection::Dome, SpiralProjection::Globe}) {
    const auto place = [&](float radius) {
      return glm::dvec3(spiralProjectedOffset(p, direction, radius,
                                              spiralLatLonOffset(direction, radius, focus), 100.0f, focus));
    };
    const auto globe = [&](float radius) { return glm::dvec3(spiralGlobeOffset(direction, radius, 100.0f, focus)); };
    // Within 2 km of the focal point every mode is the globe to 0.5 % of the distance (the
    // hyperbolic and dome modes take the Gaussian radius for the ellipsoid's two).
    EXPECT_LT(glm::length(place(3e-4f) - globe(3e-4f)), 0.005 * 1.9e3) << spiralProjectionName(p);
    EXPECT_EQ(parseSpiralProjection(spiralProjectionName(p)), p);
    if (p == SpiralProjection::Globe) continue;
    // 2000 km out they differ by far more.
    EXPECT_GT(glm::length(place(0.3f) - globe(0.3f)), 1e4) << spiralProjectionName(p);
  }
  // The hyperbolic disc holds the whole hemisphere; the dome rises where the globe falls.
  const glm::dvec3 far(spiralProjectedOffset(SpiralProjection::Hyperbolic, direction, 3.0f,
                                             {0.0f, 0.0f}, 0.0f, focus));
  EXPECT_LT(glm::length(far), 6.4e6);
  const float up = glm::dot(spiralProjectedOffset(SpiralProjection::Dome, direction, 0.3f, {}, 0.0f, focus), focus.up);
  EXPECT_GT(up, 2.5e5f);
  EXPECT_FALSE(parseSpiralProjection("mercator"));
  // The radius correction: the ends stay, the middle moves out (sqrt), below min goes to min.
  EXPECT_FLOAT_EQ(spiralCorrectedRadius(1.0f, 1.0f, 5.0f, true), 1.0f);
  EXPECT_FLOAT_EQ(spiralCorrectedRadius(5.0f, 1.0f, 5.0f, true), 5.0f);
  EXPECT_FLOAT_EQ(spiralCorrectedRadius(2.0f, 1.0f, 5.0f, true), 3.0f);
  EXPECT_FLOAT_EQ(spiralCorrectedRadius(0.0f, 1.0f, 5.0f, true), 1.0f);
  EXPECT_FLOAT_EQ(spiralCorrectedRadius(2.0f, 1.0f, 5.0f, false), 2.0f);
}

TEST(SpiralRadius, AnalyticRadiiFollowTheCamera) {
  const double earth = 6.371e6, focal = 500.0;
  const SpiralRadii low = spiralAnalyticRadii(100.0, 500.0, earth, focal, 256.0);
  const SpiralRadii high = spiralAnalyticRadii(1e5, 1e5, earth, focal, 256.0);
  // The fan's radius grows with the clearance, 1000 times higher: 1000 times larger.
  EXPECT_NEAR(high.minRad / low.minRad, 1000.0, 1e-6);
  // The fan covers its target seen from straight above.
  const double fanPx = M_PI * std::pow(low.minRad * earth / 100.0 * focal, 2.0);
  EXPECT_NEAR(fanPx, 256.0, 1e-6);
  // The horizon: from 100 km about 1130 km away (plus 340 km for the mountains beyond).
  EXPECT_NEAR(high.maxRad * earth / 1e3, 1128.0 + 339.0, 10.0);
  EXPECT_GT(high.maxRad, low.maxRad);
}

// A pixel count for the fan as a rendering would give it: the fan's disc seen straight down.
std::uint64_t fanPixelsSeen(double minRad, double clearanceM) {
  const double earth = 6.371e6, focal = 500.0;
  return std::uint64_t(M_PI * std::pow(minRad * earth / clearanceM * focal, 2.0));
}

TEST(SpiralRadius, FeedbackConvergesOnAScriptedZoomWithoutOscillating) {
  SpiralFeedbackParams params;
  SpiralRadiusFeedback feedback({1e-3, 0.5}, params);
  // Hold the camera at 1 km: the fan's pixels settle in the dead band and stay.
  double clearance = 1000.0;
  std::vector<double> radii;
  for (int frame = 0; frame < 80; ++frame) {
    feedback.update(fanPixelsSeen(feedback.radii().minRad, clearance), 10, 1e-8, M_PI);
    radii.push_back(feedback.radii().minRad);
  }
  const double pixels = double(fanPixelsSeen(feedback.radii().minRad, clearance));
  EXPECT_GT(pixels, params.fanPixels / (1.0 + params.fanBand));
  EXPECT_LT(pixels, params.fanPixels * (1.0 + params.fanBand));
  // Monotone on the way (no overshoot and back), then still.
  int reversals = 0;
  for (std::size_t i = 2; i < radii.size(); ++i) {
    const double a = radii[i - 1] - radii[i - 2], b = radii[i] - radii[i - 1];
    if (a * b < 0.0) ++reversals;
  }
  EXPECT_EQ(reversals, 0);
  EXPECT_EQ(radii[60], radii.back());
  // A zoom in, 3 % lower each frame: the radius follows, the pixels stay near the target and
  // never run away (each frame's step is bounded).
  for (int frame = 0; frame < 150; ++frame) {
    clearance *= 0.97;
    const double before = feedback.radii().minRad;
    feedback.update(fanPixelsSeen(before, clearance), 10, 1e-8, M_PI);
    EXPECT_LE(feedback.radii().minRad / before, params.maxStepFactor * 1.0001);
    EXPECT_GE(feedback.radii().minRad / before, 1.0 / (params.maxStepFactor * 1.0001));
    if (frame > 30) {
      const double seen = double(fanPixelsSeen(feedback.radii().minRad, clearance));
      EXPECT_GT(seen, params.fanPixels / 2.0) << frame;
      EXPECT_LT(seen, params.fanPixels * 2.0) << frame;
    }
  }
  // The last revolution: hidden shrinks the maximum, visible grows it, a trace keeps it.
  const double maxRad = feedback.radii().maxRad;
  feedback.update(fanPixelsSeen(feedback.radii().minRad, clearance), 0, 1e-8, M_PI);
  EXPECT_LT(feedback.radii().maxRad, maxRad);
  const double shrunk = feedback.radii().maxRad;
  feedback.update(fanPixelsSeen(feedback.radii().minRad, clearance), 2, 1e-8, M_PI);
  EXPECT_EQ(feedback.radii().maxRad, shrunk);
  feedback.update(fanPixelsSeen(feedback.radii().minRad, clearance), 500, 1e-8, M_PI);
  EXPECT_GT(feedback.radii().maxRad, shrunk);
}

}  // namespace
}  // namespace tellus
