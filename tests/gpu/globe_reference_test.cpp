// The globe reference renderer: no jitter 2 m above the ground on the far side of the planet
// (the surface reconstructed from depth stays on the ellipsoid to millimetres while the camera
// moves in 1 cm steps), and the whole Earth from orbit (ETOPO5): a disc of the predicted size
// without a hole, with land and sea where they belong.
#include <cmath>

#include <gtest/gtest.h>
#include <glm/geometric.hpp>

#include "support/gl_test.hpp"
#include "support/terrain_fixtures.hpp"
#include "support/test_support.hpp"
#include "tellus/core/geo_camera.hpp"
#include "tellus/core/geodesy.hpp"
#include "tellus/core/rgb_image.hpp"
#include "tellus/dem/dem_loader.hpp"
#include "tellus/render/globe/globe_reference_renderer.hpp"

namespace tellus {
namespace {

using GlobeReferenceTest = test::GlTest;
using wgs84::kDegree;

// A flat grid 100 m above the ellipsoid, 1 arc-second samples, around (lat, lon).
HeightGrid flatPatch(double latDeg, double lonDeg, int samples) {
  HeightGrid grid(samples, samples);
  const double step = 1.0 / 3600.0;
  grid.georef.isGeographic = true;
  grid.georef.hasGeoTransform = true;
  grid.georef.crsName = "WGS 84";
  const double west = lonDeg - 0.5 * (samples - 1) * step;
  const double north = latDeg + 0.5 * (samples - 1) * step;
  grid.georef.geoTransform = {west - 0.5 * step, step, 0.0, north + 0.5 * step, 0.0, -step};
  std::fill(grid.heights.begin(), grid.heights.end(), 100.0f);
  return grid;
}

// 2 m above a flat surface at (0.5 S, 179.5 E), where ECEF x is -6.4e6 m and float steps are
// half a metre: the camera walks east in 1 cm steps, and in every frame every pixel within 30 m
// reconstructs to a point 100 m above the ellipsoid within 5 mm (sagging chords of 30 m cells
// add at most 0.02 mm). Without positions relative to the eye the error would be float steps of
// the ECEF coordinates, decimetres.
TEST_F(GlobeReferenceTest, NoJitterTwoMetresAboveTheGroundOnTheFarSide) {
  const HeightGrid grid = flatPatch(-0.5, 179.5, 65);
  Result<GlobeReferenceRenderer> renderer = GlobeReferenceRenderer::create(grid, nullptr);
  ASSERT_TRUE(renderer) << renderer.error().message;
  double worstM = 0.0;
  int measured = 0;
  for (int step = 0; step < 5; ++step) {
    GeoCamera camera{-0.5, 179.5, 102.0, 80.0, -20.0, 60.0};
    camera.lonDeg += step * 0.01 / (wgs84::kSemiMajorAxisM * kDegree);  // 1 cm east per step
    const ViewSetup view =
        geoViewSetup(camera, chooseGeoClipRange(camera, 100.0, 100.0), 320, 240);
    const test::RenderedFrame frame = test::renderFrame(renderer.value(), view);
    for (int y = 0; y < view.height; y += 3) {
      for (int x = 0; x < view.width; x += 3) {
        const float d = frame.depth.at(x, y);
        if (d <= 0.0f) continue;
        const glm::dvec3 p = view.unprojectPixel({x + 0.5, y + 0.5}, d);
        if (glm::distance(p, view.camera.position) > 30.0) continue;
        worstM = std::max(worstM, std::abs(wgs84::ecefToGeodetic(p).heightM - 100.0));
        ++measured;
      }
    }
  }
  EXPECT_GT(measured, 2000);
  EXPECT_LT(worstM, 0.005);
  RecordProperty("worst_mm", std::to_string(worstM * 1000.0));
}

// Half a globe of ETOPO5 seen from 15,000 km above (30 N, 120 E).
TEST_F(GlobeReferenceTest, TheWholeEarthFromOrbit) {
  TELLUS_REQUIRE_SHARED_DATA(data);
  Result<HeightGrid> etopo = loadDem({data / "etopo5-global/etopo5_int16.tif"});
  ASSERT_TRUE(etopo) << etopo.error().message;
  Result<GlobeReferenceRenderer> renderer = GlobeReferenceRenderer::create(etopo.value(), nullptr);
  ASSERT_TRUE(renderer) << renderer.error().message;
  const GeoCamera camera{30.0, 120.0, 15'000'000.0, 0.0, -90.0, 45.0};
  const int size = 400;
  const ViewSetup view = geoViewSetup(
      camera, chooseGeoClipRange(camera, renderer->highestM(), renderer->highestM()), size, size);
  const test::RenderedFrame frame = test::renderFrame(renderer.value(), view);
  ASSERT_TRUE(writePng(frame.colour, test::testOutputDir() / "globe-earth-from-orbit.png"));

  // The disc's radius: the Earth subtends asin(R / (R + H)) (R the local radius, 6,373 km at
  // 30 N), so its edge lies tan of that over tan(fov / 2) of the half image from the centre.
  const double r = glm::length(wgs84::geodeticToEcef({30.0 * kDegree, 120.0 * kDegree, 0.0}));
  const double expected = std::tan(std::asin(r / (r + camera.altitudeM))) /
                          std::tan(0.5 * camera.fovYDeg * kDegree) * 0.5 * size;
  const auto isTerrain = [&](int x, int y) { return frame.depth.at(x, y) > 0.0f; };
  int left = size / 2, right = size / 2;
  while (left > 0 && isTerrain(left - 1, size / 2)) --left;
  while (right < size - 1 && isTerrain(right + 1, size / 2)) ++right;
  EXPECT_NEAR(0.5 * (right - left + 1), expected, 3.0);
  // No cracks: every pixel inside the disc (2 px in from its edge) is terrain, across the 256-cell
  // chunk seams and the antimeridian seam (in view at 45 N, inside the disc tested).
  int holes = 0, inside = 0;
  for (int y = 0; y < size; ++y) {
    for (int x = 0; x < size; ++x) {
      if (std::hypot(x + 0.5 - 0.5 * size, y + 0.5 - 0.5 * size) > expected - 2.0) continue;
      ++inside;
      holes += isTerrain(x, y) ? 0 : 1;
    }
  }
  EXPECT_GT(inside, 50000);
  EXPECT_EQ(holes, 0);
  glm::dvec2 antimeridian;
  ASSERT_TRUE(view.projectToPixel(wgs84::geodeticToEcef({45.0 * kDegree, 180.0 * kDegree, 0.0}),
                                  antimeridian));
  EXPECT_LT(std::hypot(antimeridian.x - 0.5 * size, antimeridian.y - 0.5 * size), expected - 10.0);

  // Land and sea where they belong: the Tibetan plateau (32 N, 88 E) is high and bright, the
  // Pacific east of the Philippines (15 N, 140 E) blue, the Gobi (43 N, 105 E) land.
  const auto colourAt = [&](double latDeg, double lonDeg, double heightM) {
    glm::dvec2 pixel;
    EXPECT_TRUE(view.projectToPixel(
        wgs84::geodeticToEcef({latDeg * kDegree, lonDeg * kDegree, heightM}), pixel));
    const std::uint8_t* c = frame.colour.at(int(pixel.x), int(pixel.y));
    return glm::ivec3(c[0], c[1], c[2]);
  };
  const glm::ivec3 tibet = colourAt(32.0, 88.0, 5000.0);
  EXPECT_GT(tibet.r + tibet.g + tibet.b, 3 * 180) << tibet.r << "," << tibet.g << "," << tibet.b;
  const glm::ivec3 pacific = colourAt(15.0, 140.0, -5000.0);
  EXPECT_GT(pacific.b, pacific.r + 20) << pacific.r << "," << pacific.g << "," << pacific.b;
  const glm::ivec3 gobi = colourAt(43.0, 105.0, 1000.0);
  EXPECT_GT(gobi.r, gobi.b) << gobi.r << "," << gobi.g << "," << gobi.b;
}

// A drape and the sky: a sea-level globe draped with a map red west of Greenwich and green east
// of it, seen from 8,000 km over (0 N, 0 E) with the atmosphere behind it. Each hemisphere
// shows its colour, space is dark, the limb glows blue; without the sky the background is the
// clear colour untouched (what the bench's crack test relies on).
TEST_F(GlobeReferenceTest, DrapeAndSky) {
  HeightGrid globe(180, 91);  // 2-degree samples, all longitudes, pole to pole, 0 m
  globe.georef.isGeographic = true;
  globe.georef.hasGeoTransform = true;
  globe.georef.crsName = "WGS 84";
  globe.georef.geoTransform = {-181.0, 2.0, 0.0, 91.0, 0.0, -2.0};
  DrapeImage drape;
  drape.image = RgbImage(360, 180);
  for (int y = 0; y < 180; ++y) {
    for (int x = 0; x < 360; ++x) {
      std::uint8_t* p = drape.image.at(x, y);
      p[0] = x < 180 ? 200 : 20;
      p[1] = x < 180 ? 20 : 200;
      p[2] = 20;
    }
  }
  Result<GlobeReferenceRenderer> renderer = GlobeReferenceRenderer::create(globe, nullptr, &drape);
  ASSERT_TRUE(renderer) << renderer.error().message;
  const GeoCamera camera{0.0, 0.0, 8'000'000.0, 0.0, -90.0, 70.0};
  const int size = 256;
  const ViewSetup view =
      geoViewSetup(camera, chooseGeoClipRange(camera, 0.0, 0.0), size, size);
  RenderSettings settings;
  settings.sky = true;
  const test::RenderedFrame frame = test::renderFrame(renderer.value(), view, settings);
  ASSERT_TRUE(writePng(frame.colour, test::testOutputDir() / "globe-drape-and-sky.png"));
  const auto colourAt = [&](double latDeg, double lonDeg) {
    glm::dvec2 pixel;
    EXPECT_TRUE(view.projectToPixel(
        wgs84::geodeticToEcef({latDeg * kDegree, lonDeg * kDegree, 0.0}), pixel));
    const std::uint8_t* c = frame.colour.at(int(pixel.x), int(pixel.y));
    return glm::ivec3(c[0], c[1], c[2]);
  };
  const glm::ivec3 west = colourAt(0.0, -30.0), east = colourAt(0.0, 30.0);
  EXPECT_GT(west.r, west.g + 40) << west.r << "," << west.g << "," << west.b;
  EXPECT_GT(east.g, east.r + 40) << east.r << "," << east.g << "," << east.b;
  const std::uint8_t* corner = frame.colour.at(0, 0);
  EXPECT_LT(corner[0] + corner[1] + corner[2], 60) << "space is dark";
  // At the disc's edge, on the sunlit side: the atmosphere's rim (60 km: a pixel or two from
  // here), blue and brighter than space.
  const double r = 6'378'137.0;
  const double radiusPx = std::tan(std::asin(r / (r + camera.altitudeM))) /
                          std::tan(0.5 * camera.fovYDeg * kDegree) * 0.5 * size;
  int bestBlue = 0;
  for (int y = 0; y < size; ++y) {
    for (int x = 0; x < size; ++x) {
      const double d = std::hypot(x + 0.5 - 0.5 * size, y + 0.5 - 0.5 * size);
      if (d < radiusPx - 0.5 || d > radiusPx + 2.0) continue;
      const std::uint8_t* c = frame.colour.at(x, y);
      if (c[2] > c[0] + 20) bestBlue = std::max<int>(bestBlue, c[2]);
    }
  }
  EXPECT_GT(bestBlue, 60) << "no blue rim around the globe";

  settings.sky = false;
  const test::RenderedFrame plain = test::renderFrame(renderer.value(), view, settings);
  const std::uint8_t* background = plain.colour.at(0, 0);
  EXPECT_EQ(background[0], test::kSentinel[0]);
  EXPECT_EQ(background[1], test::kSentinel[1]);
  EXPECT_EQ(background[2], test::kSentinel[2]);
}

TEST_F(GlobeReferenceTest, RefusesAProjectedDem) {
  HeightGrid utm(8, 8);
  utm.georef.hasGeoTransform = true;
  utm.georef.crsName = "WGS 84 / UTM zone 52N";
  Result<GlobeReferenceRenderer> renderer = GlobeReferenceRenderer::create(utm, nullptr);
  ASSERT_FALSE(renderer);
  EXPECT_NE(renderer.error().message.find("latitude/longitude"), std::string::npos);
}

}  // namespace
}  // namespace tellus
