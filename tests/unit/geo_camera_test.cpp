// Cameras on the globe: axes from heading and pitch in the local ENU frame, projections in ECEF,
// near and far from the altitude and the horizon, parsing and refusals.
#include <cmath>

#include <gtest/gtest.h>
#include <glm/geometric.hpp>

#include "tellus/core/enu_frame.hpp"
#include "tellus/core/geo_camera.hpp"
#include "tellus/core/geodesy.hpp"

namespace tellus {
namespace {

using wgs84::kDegree;

TEST(GeoCamera, AxesFollowHeadingAndPitchInTheLocalFrame) {
  const GeoCamera camera{35.337, 127.731, 3000.0, 90.0, 0.0, 60.0};  // over Jirisan, east
  const GeoCameraFrame frame = geoCameraFrame(camera);
  const EnuFrame enu({camera.latDeg * kDegree, camera.lonDeg * kDegree, camera.altitudeM});
  EXPECT_NEAR(glm::distance(frame.eye, enu.originEcef()), 0.0, 1e-6);
  EXPECT_NEAR(glm::distance(frame.forward, enu.east()), 0.0, 1e-12);
  EXPECT_NEAR(glm::distance(frame.right, -enu.north()), 0.0, 1e-12);
  EXPECT_NEAR(glm::distance(frame.up, enu.up()), 0.0, 1e-12);
  const GeoCameraFrame down = geoCameraFrame({10.0, -70.0, 500.0, 0.0, -90.0, 45.0});
  const EnuFrame there({10.0 * kDegree, -70.0 * kDegree, 500.0});
  EXPECT_NEAR(glm::distance(down.forward, -there.up()), 0.0, 1e-12);
  EXPECT_NEAR(glm::length(down.up), 1.0, 1e-12);
  EXPECT_NEAR(glm::dot(down.up, down.forward), 0.0, 1e-12);
}

TEST(GeoCamera, TheGroundUnderALookDownCameraIsTheImageCentre) {
  const GeoCamera camera{-33.9, 18.4, 2500.0, 30.0, -90.0, 50.0};
  const ClipRange clip = chooseGeoClipRange(camera, 0.0, 3000.0);
  const ViewSetup view = geoViewSetup(camera, clip, 640, 480);
  const glm::dvec3 ground =
      wgs84::geodeticToEcef({camera.latDeg * kDegree, camera.lonDeg * kDegree, 0.0});
  glm::dvec2 pixel;
  double depth = 0.0;
  ASSERT_TRUE(view.projectToPixel(ground, pixel, &depth));
  EXPECT_NEAR(pixel.x, 320.0, 1e-6);
  EXPECT_NEAR(pixel.y, 240.0, 1e-6);
  EXPECT_GT(depth, 0.0);
  EXPECT_LT(depth, 1.0);
  EXPECT_NEAR(glm::distance(view.unprojectPixel(pixel, depth), ground), 0.0, 1e-4);
  // Heading 30: the ground 100 m north of the centre lies up and to the left (the image's top
  // points along the heading).
  const EnuFrame enu({camera.latDeg * kDegree, camera.lonDeg * kDegree, 0.0});
  glm::dvec2 north;
  ASSERT_TRUE(view.projectToPixel(enu.toEcef({0.0, 100.0, 0.0}), north));
  EXPECT_LT(north.y, 240.0);
  EXPECT_LT(north.x, 320.0);
}

TEST(GeoCamera, NearAndFarReachTheHorizon) {
  // 2 m above ground at sea level: near 1 m; far beyond the horizon (5 km) and beyond where
  // 3000 m mountains still show (about 200 km plus the ellipsoid's a - b slack).
  const GeoCamera walker{45.0, 7.0, 2.0, 0.0, 0.0, 60.0};
  const ClipRange low = chooseGeoClipRange(walker, 0.0, 3000.0);
  EXPECT_DOUBLE_EQ(low.nearM, 1.0);
  EXPECT_GT(low.farM, 200'000.0);
  EXPECT_LT(low.farM, 1'000'000.0);
  // From 20,000 km the whole visible disc, limb included, lies inside near..far.
  const GeoCamera orbit{0.0, 0.0, 20'000'000.0, 0.0, -90.0, 40.0};
  const ClipRange far = chooseGeoClipRange(orbit, 0.0, 8848.0);
  const ViewSetup view = geoViewSetup(orbit, far, 512, 512);
  for (const double lonDeg : {0.0, 30.0, 60.0, 75.0}) {
    const glm::dvec3 p = wgs84::geodeticToEcef({0.0, lonDeg * kDegree, 0.0});
    glm::dvec2 pixel;
    double depth = 0.0;
    ASSERT_TRUE(view.projectToPixel(p, pixel, &depth)) << lonDeg;
    EXPECT_GT(depth, 0.0) << lonDeg;  // in front of the far plane
    EXPECT_LT(depth, 1.0) << lonDeg;  // beyond the near plane
  }
}

TEST(GeoCamera, ParsesAndRefusesNonsense) {
  Result<GeoCamera> ok = parseGeoCamera("35.337,127.731,2000,45,-20,60");
  ASSERT_TRUE(ok) << ok.error().message;
  EXPECT_DOUBLE_EQ(ok->lonDeg, 127.731);
  EXPECT_DOUBLE_EQ(ok->pitchDeg, -20.0);
  for (const char* bad : {"91,0,1000,0,0,60", "0,0,1000,0,-95,60", "0,0,nan,0,0,60",
                          "0,0,1000,0,0,0", "0,0,1e308,0,0,60", "0,0,1000,0,0", "a,b,c,d,e,f",
                          "0,0,1000,0,0,60,7", "0,0,-20000,0,0,60"}) {
    EXPECT_FALSE(parseGeoCamera(bad)) << bad;
  }
}

}  // namespace
}  // namespace tellus

namespace tellus {
namespace {

TEST(GeoViewFootprint, CoversWhatTheViewShows) {
  // Straight down from 1000 km with a 40-degree field: about +-3.3 degrees of latitude (and a
  // 24th more on each side, the margin between rays).
  const GeoFootprint down = geoViewFootprint({41.0, 11.0, 1'000'000.0, 0.0, -90.0, 40.0}, 1.0, 0.0);
  EXPECT_LT(down.southDeg, 41.0);
  EXPECT_GT(down.northDeg, 41.0);
  EXPECT_NEAR(down.northDeg - down.southDeg, 6.6 * 26.0 / 24.0, 0.5);
  EXPECT_LT(down.westDeg, 11.0);
  EXPECT_GT(down.eastDeg, 11.0);
  // 2 km up looking north: the horizon (160 km) and terrain behind it lie north, not south.
  const GeoFootprint north = geoViewFootprint({35.0, 127.5, 2000.0, 0.0, -10.0, 60.0}, 16.0 / 9.0, 2000.0);
  EXPECT_LT(north.southDeg, 35.0);
  EXPECT_GT(north.southDeg, 34.6);
  EXPECT_GT(north.northDeg, 35.0 + 2.0);
  EXPECT_LT(north.northDeg, 35.0 + 3.5);
  // Across the antimeridian, and near a pole: every longitude.
  const GeoFootprint seam = geoViewFootprint({0.0, 179.9, 50'000.0, 90.0, -30.0, 60.0}, 1.5, 0.0);
  EXPECT_EQ(seam.westDeg, -180.0);
  EXPECT_EQ(seam.eastDeg, 180.0);
  const GeoFootprint pole = geoViewFootprint({89.5, 0.0, 200'000.0, 0.0, -60.0, 60.0}, 1.5, 0.0);
  EXPECT_EQ(pole.westDeg, -180.0);
  EXPECT_EQ(pole.northDeg, 90.0);
  // From orbit the whole disc: beyond +-60 degrees around the nadir.
  const GeoFootprint orbit = geoViewFootprint({30.0, 120.0, 15'000'000.0, 0.0, -90.0, 45.0}, 1.5, 0.0);
  EXPECT_LT(orbit.southDeg, -25.0);
}

}  // namespace
}  // namespace tellus

namespace tellus {
namespace {

// From 18,000 km over 25 N the north pole is on the visible side of the globe though no ray of
// the sampled grid lands on it.
TEST(GeoViewFootprint, TakesInAVisiblePole) {
  const GeoFootprint f = geoViewFootprint({25.0, -70.0, 18'000'000.0, 0.0, -90.0, 40.0}, 1.0, 0.0);
  EXPECT_EQ(f.northDeg, 90.0);
  EXPECT_EQ(f.westDeg, -180.0);
  EXPECT_GT(f.southDeg, -90.0);
}

}  // namespace
}  // namespace tellus
