// The harness on the globe, GL-free: the globe reference's surface as ground truth
// (GlobeSurface) and the globe camera paths.
#include <cmath>

#include <gtest/gtest.h>

#include "tellus/core/geodesy.hpp"
#include "tellus/eval/geo_camera_path.hpp"
#include "support/terrain_fixtures.hpp"
#include "support/test_support.hpp"
#include "tellus/eval/globe_surface.hpp"
#include "tellus/eval/store_surface.hpp"
#include "tellus/tiles/global_store_builder.hpp"
#include "tellus/lod/globe/globe_mesh.hpp"
#include "tellus/tiles/global_store.hpp"

namespace tellus {
namespace {

// 0.01-degree samples over 127..127.5 E, 35.5..35 N, rough heights.
HeightGrid roughGrid() {
  HeightGrid grid(51, 51);
  for (int j = 0; j < 51; ++j) {
    for (int i = 0; i < 51; ++i) {
      grid.at(i, j) = float(1000.0 + 300.0 * std::sin(i * 0.7) * std::cos(j * 1.1) + 7.0 * ((i * 31 + j * 17) % 5));
    }
  }
  grid.georef.crsWkt = kWgs84Wkt;
  grid.georef.isGeographic = true;
  grid.georef.hasGeoTransform = true;
  grid.georef.geoTransform = {127.0 - 0.005, 0.01, 0.0, 35.5 + 0.005, 0.0, -0.01};
  return grid;
}

TEST(GlobeSurface, IsTheReferenceMesh) {
  const HeightGrid grid = roughGrid();
  const GlobeSurface surface(grid, nullptr);
  Result<globe::GlobeMesh> mesh = globe::buildGlobeMesh(grid, nullptr, 16);
  ASSERT_TRUE(mesh);
  // Every vertex of the reference mesh is on the surface: it maps to itself.
  double worst = 0.0;
  for (const globe::GlobeChunk& chunk : mesh->chunks) {
    for (const globe::GlobeVertex& v : chunk.vertices) {
      const glm::dvec3 p = globe::vertexEcef(v);
      glm::dvec3 s;
      ASSERT_TRUE(surface.trueSurfacePoint(p, s))
          << wgs84::ecefToGeodetic(p).latRad / wgs84::kDegree << " "
          << wgs84::ecefToGeodetic(p).lonRad / wgs84::kDegree;
      worst = std::max(worst, glm::length(s - p));
    }
  }
  EXPECT_LT(worst, 1e-3);
  // A point 25 m above the triangle (along the normal) comes back down onto it; the height of
  // the surface there is that of the mesh.
  const double lat = 35.2037, lon = 127.3141;
  const double h = surface.ellipsoidalHeightM(lat, lon);
  ASSERT_TRUE(std::isfinite(h));
  const glm::dvec3 above = wgs84::geodeticToEcef({lat * wgs84::kDegree, lon * wgs84::kDegree, h + 25.0});
  glm::dvec3 s;
  ASSERT_TRUE(surface.trueSurfacePoint(above, s));
  EXPECT_NEAR(glm::length(s - above), 25.0, 1e-3);
  EXPECT_NEAR(wgs84::ecefToGeodetic(s).heightM, h, 1e-3);
  // Inside a cell the surface is the NE-SW triangle's plane, not the bilinear patch: at the
  // cell centre it is the mean of the NE and SW samples, less the chord's sag below the
  // ellipsoid (a 1.4 km diagonal sags 3.8 cm).
  const double centreLat = 35.5 - 10.5 * 0.01, centreLon = 127.0 + 20.5 * 0.01;
  EXPECT_NEAR(surface.ellipsoidalHeightM(centreLat, centreLon),
              0.5 * (grid.at(21, 10) + grid.at(20, 11)) - 0.038, 0.005);
  // Outside the grid there is no truth.
  EXPECT_FALSE(std::isfinite(surface.ellipsoidalHeightM(36.0, 127.2)));
}

TEST(GeoCameraPath, DescentOrbitLowflightWalk) {
  const GroundHeightFn ground = [](double lat, double lon) {
    return 500.0 + 100.0 * std::sin(lat * 10.0) + 50.0 * std::cos(lon * 7.0);
  };
  const GeoPathTarget jirisan{35.337, 127.731};
  Result<GeoCameraPath> descent = makeGeoCameraPath("descent", ground, jirisan);
  ASSERT_TRUE(descent) << descent.error().message;
  const std::vector<GeoCamera> d = descent->sample(50);
  EXPECT_NEAR(d.front().altitudeM, 20'000'000.0, 1000.0);
  EXPECT_NEAR(d.back().altitudeM, ground(35.337, 127.731) + 2.0, 1e-6);
  EXPECT_EQ(d.front().pitchDeg, -90.0);
  EXPECT_NEAR(d.back().pitchDeg, -15.0, 1e-9);
  for (std::size_t i = 1; i < d.size(); ++i) EXPECT_LT(d[i].altitudeM, d[i - 1].altitudeM);
  // Geometric in altitude: half way down in time is the geometric mean, not 10,000 km.
  EXPECT_LT(descent->at(30.0).altitudeM, 20'000.0);

  Result<GeoCameraPath> orbit = makeGeoCameraPath("orbit", ground, jirisan);
  ASSERT_TRUE(orbit);
  for (const GeoCamera& c : orbit->sample(37)) EXPECT_EQ(c.altitudeM, 10'000'000.0);
  // Once round (a geodesic on the ellipsoid does not close exactly).
  EXPECT_NEAR(orbit->sample(2).back().latDeg, jirisan.latDeg, 0.5);

  Result<GeoCameraPath> flight = makeGeoCameraPath("lowflight", ground, jirisan);
  ASSERT_TRUE(flight);
  for (const GeoCamera& c : flight->sample(40)) {
    EXPECT_GE(c.altitudeM, ground(c.latDeg, c.lonDeg) + 300.0) << "well above the ground";
  }
  Result<GeoCameraPath> walk = makeGeoCameraPath("walk", ground, jirisan);
  ASSERT_TRUE(walk);
  const GeoCamera end = walk->sample(2).back();
  EXPECT_NEAR(end.altitudeM, ground(end.latDeg, end.lonDeg) + 2.0, 1e-6);
  EXPECT_GT(end.lonDeg, jirisan.lonDeg + 0.02);

  // A target where the data has no ground is refused, naming the place.
  const GroundHeightFn none = [](double, double) { return std::nan(""); };
  Result<GeoCameraPath> nowhere = makeGeoCameraPath("descent", none, jirisan);
  ASSERT_FALSE(nowhere);
  EXPECT_NE(nowhere.error().message.find("no ground"), std::string::npos);
  EXPECT_FALSE(makeGeoCameraPath("spiral", ground, jirisan));
}

TEST(GeoCameraPath, KeyframeFiles) {
  Result<GeoCameraPath> path = parseGeoCameraPath(
      R"({"keyframes": [{"time": 0, "lat": 10, "lon": 179, "alt": 1000},
                        {"time": 2, "lat": 12, "lon": -179, "alt": 4000, "heading": 90}]})",
      "test");
  ASSERT_TRUE(path) << path.error().message;
  const GeoCamera mid = path->at(1.0);
  EXPECT_NEAR(mid.latDeg, 11.0, 1e-12);
  EXPECT_NEAR(std::abs(mid.lonDeg), 180.0, 1e-9) << "across the antimeridian, the short way";
  EXPECT_NEAR(mid.altitudeM, 2000.0, 1e-9) << "geometric";
  EXPECT_NEAR(mid.headingDeg, 45.0, 1e-12);
  EXPECT_FALSE(parseGeoCameraPath("{", "bad"));
  EXPECT_FALSE(parseGeoCameraPath(R"({"keyframes": [{"time": 0, "lat": 10, "lon": 0, "alt": 1}]})", "one"));
  EXPECT_FALSE(parseGeoCameraPath(
      R"({"keyframes": [{"time": 0, "lat": 10, "lon": 0, "alt": 1}, {"time": 0, "lat": 1, "lon": 0, "alt": 1}]})",
      "same time"));
  Result<GeoCameraPath> noLat = parseGeoCameraPath(
      R"({"keyframes": [{"time": 0, "lon": 0, "alt": 1}, {"time": 1, "lat": 1, "lon": 0, "alt": 1}]})", "x");
  ASSERT_FALSE(noLat);
  EXPECT_NE(noLat.error().message.find("lat, lon, alt"), std::string::npos);
  EXPECT_FALSE(parseGeoCameraPath(
      R"({"keyframes": [{"time": 0, "lat": 95, "lon": 0, "alt": 1}, {"time": 1, "lat": 1, "lon": 0, "alt": 1}]})",
      "lat 95"));
}

// The bench's truth over a store is the globe reference drawing the store at its deepest depth
// everywhere: where the store holds that depth and where it is sparse (upsampled ancestors).
TEST(StoreSurface, IsTheGlobeReferenceAtTheStoresDeepestDepth) {
  namespace fs = std::filesystem;
  const fs::path dir = test::freshTestDir();
  test::buildSparseGlobalStore(dir);
  Result<std::shared_ptr<GlobalStore>> store = GlobalStore::open(dir / "store.tstore");
  ASSERT_TRUE(store);
  const int deepest = store.value()->metadata().deepestDepth;
  ASSERT_GE(deepest, 6);
  // The reference's grid at the deepest depth over the fine area and sparse ground around it.
  Result<HeightGrid> region =
      readGlobalRegion(*store.value(), deepest, {9.0, 39.0, 13.0, 43.0});
  ASSERT_TRUE(region);
  const GlobeSurface reference(region.value(), nullptr);
  StoreSurface truth(store.value(), nullptr);
  EXPECT_EQ(truth.depth(), deepest);
  double worst = 0.0;
  int sparse = 0;
  for (int k = 0; k < 400; ++k) {
    const double lat = 39.2 + 3.6 * ((k * 37) % 400) / 400.0;
    const double lon = 9.2 + 3.6 * ((k * 91) % 400) / 400.0;
    const double expected = reference.ellipsoidalHeightM(lat, lon);
    ASSERT_TRUE(std::isfinite(expected));
    const double d = std::abs(truth.ellipsoidalHeightM(lat, lon) - expected);
    worst = std::max(worst, d);
    sparse += lat < 40.0 || lat > 42.0 || lon < 10.0 || lon > 12.0 ? 1 : 0;
  }
  EXPECT_LT(worst, 1e-3);
  EXPECT_GT(sparse, 100);  // the sparse ground was measured too
  // A drawn point above the ground maps onto it, along the ellipsoid's normal.
  const glm::dvec3 above =
      wgs84::geodeticToEcef({41.3 * wgs84::kDegree, 11.2 * wgs84::kDegree, 5000.0});
  glm::dvec3 onGround;
  ASSERT_TRUE(truth.trueSurfacePoint(above, onGround));
  EXPECT_NEAR(wgs84::ecefToGeodetic(onGround).heightM, reference.ellipsoidalHeightM(41.3, 11.2),
              1e-3);
}

}  // namespace
}  // namespace tellus
