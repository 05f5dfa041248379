// The globe reference's mesh: vertices on the ellipsoid to the micrometre (high + low floats),
// the samples chunks share bit-identical, normals in the local frame, the antimeridian seam
// closed for global grids, the geoid applied, non-geographic grids refused.
#include <algorithm>
#include <cmath>

#include <gtest/gtest.h>
#include <glm/geometric.hpp>

#include "support/test_support.hpp"
#include "tellus/core/geodesy.hpp"
#include "tellus/lod/globe/globe_mesh.hpp"

namespace tellus {
namespace {

using wgs84::kDegree;

// A grid of `w` x `h` samples `stepDeg` apart whose north-west sample is at (lat, lon).
HeightGrid geographicGrid(int w, int h, double latDeg, double lonDeg, double stepDeg) {
  HeightGrid grid(w, h);
  grid.georef.isGeographic = true;
  grid.georef.hasGeoTransform = true;
  grid.georef.crsName = "WGS 84";
  grid.georef.geoTransform = {lonDeg - 0.5 * stepDeg, stepDeg, 0.0,
                              latDeg + 0.5 * stepDeg, 0.0, -stepDeg};
  return grid;
}

TEST(GlobeMesh, VerticesSitOnTheEllipsoidToTheMicrometre) {
  HeightGrid grid = geographicGrid(9, 7, 35.5, 127.0, 0.01);
  for (int r = 0; r < grid.height; ++r)
    for (int c = 0; c < grid.width; ++c) grid.at(c, r) = float(100 * c + 10 * r);
  Result<globe::GlobeMesh> mesh = globe::buildGlobeMesh(grid, nullptr, 4);
  ASSERT_TRUE(mesh) << mesh.error().message;
  ASSERT_EQ(mesh->chunks.size(), 4u);  // 8 x 6 cells in chunks of 4: 2 x 2
  EXPECT_EQ(mesh->triangleCount, 8u * 6u * 2u);
  const globe::GlobeChunk& first = mesh->chunks[0];
  ASSERT_EQ(first.vertsX, 5);
  for (int j = 0; j < first.vertsY; ++j) {
    for (int i = 0; i < first.vertsX; ++i) {
      const globe::GlobeVertex& v = first.vertices[std::size_t(j * first.vertsX + i)];
      const glm::dvec3 expected = wgs84::geodeticToEcef(
          {(35.5 - 0.01 * j) * kDegree, (127.0 + 0.01 * i) * kDegree, grid.at(i, j)});
      EXPECT_LT(glm::distance(globe::vertexEcef(v), expected), 1e-6) << i << "," << j;
      EXPECT_EQ(v.heightM, grid.at(i, j));
    }
  }
  // The eastern column of chunk 0 is the western column of chunk 1, bit for bit.
  const globe::GlobeChunk& second = mesh->chunks[1];
  for (int j = 0; j < first.vertsY; ++j) {
    const globe::GlobeVertex& a = first.vertices[std::size_t(j * first.vertsX + 4)];
    const globe::GlobeVertex& b = second.vertices[std::size_t(j * second.vertsX)];
    EXPECT_EQ(a.whole, b.whole);
    EXPECT_EQ(a.fraction, b.fraction);
  }
}

// A skirt: one ring of vertices around the grid, under its edge samples by skirtM, the inside
// vertices where they were; the grid's index pattern then draws the walls.
TEST(GlobeMesh, ASkirtHangsUnderEveryEdgeSample) {
  HeightGrid grid = geographicGrid(5, 4, 35.5, 127.0, 0.01);
  for (int r = 0; r < grid.height; ++r)
    for (int c = 0; c < grid.width; ++c) grid.at(c, r) = float(100 * c + 10 * r);
  Result<globe::GlobeMesh> mesh = globe::buildGlobeMesh(grid, nullptr, 16, 50.0);
  ASSERT_TRUE(mesh) << mesh.error().message;
  ASSERT_EQ(mesh->chunks.size(), 1u);
  const globe::GlobeChunk& chunk = mesh->chunks[0];
  ASSERT_EQ(chunk.vertsX, 7);
  ASSERT_EQ(chunk.vertsY, 6);
  EXPECT_EQ(mesh->triangleCount, 6u * 5u * 2u);
  for (int j = 0; j < chunk.vertsY; ++j) {
    for (int i = 0; i < chunk.vertsX; ++i) {
      const int col = std::clamp(i - 1, 0, grid.width - 1), row = std::clamp(j - 1, 0, grid.height - 1);
      const bool ring = i == 0 || j == 0 || i == chunk.vertsX - 1 || j == chunk.vertsY - 1;
      const glm::dvec3 expected = wgs84::geodeticToEcef(
          {(35.5 - 0.01 * row) * kDegree, (127.0 + 0.01 * col) * kDegree,
           grid.at(col, row) - (ring ? 50.0 : 0.0)});
      const globe::GlobeVertex& v = chunk.vertices[std::size_t(j * chunk.vertsX + i)];
      EXPECT_LT(glm::distance(globe::vertexEcef(v), expected), 1e-6) << i << "," << j;
      EXPECT_EQ(v.heightM, grid.at(col, row));
    }
  }
  EXPECT_FALSE(globe::buildGlobeMesh(grid, nullptr, 16, -1.0));
  HeightGrid world = geographicGrid(36, 5, 80.0, -180.0 + 5.0, 10.0);
  EXPECT_FALSE(globe::buildGlobeMesh(world, nullptr, 16, 10.0)) << "no edge around all longitudes";
}

TEST(GlobeMesh, NormalsAreInTheLocalFrame) {
  HeightGrid flat = geographicGrid(5, 5, -10.0, 40.0, 0.001);
  Result<globe::GlobeMesh> level = globe::buildGlobeMesh(flat, nullptr, 8);
  ASSERT_TRUE(level);
  const glm::vec3 up = globe::unpackNormal(level->chunks[0].vertices[12].normal);
  EXPECT_NEAR(up.z, 1.0f, 2e-3f);
  // Heights rising eastwards: the normal leans west.
  HeightGrid slope = flat;
  for (int r = 0; r < slope.height; ++r)
    for (int c = 0; c < slope.width; ++c) slope.at(c, r) = float(50 * c);
  Result<globe::GlobeMesh> tilted = globe::buildGlobeMesh(slope, nullptr, 8);
  ASSERT_TRUE(tilted);
  const glm::vec3 n = globe::unpackNormal(tilted->chunks[0].vertices[12].normal);
  EXPECT_LT(n.x, -0.3f);
  EXPECT_NEAR(n.y, 0.0f, 2e-3f);
  EXPECT_GT(n.z, 0.5f);
}

TEST(GlobeMesh, HeightsAboveTheGeoidBecomeEllipsoidal) {
  TELLUS_REQUIRE_SHARED_DATA(data);
  Result<Geoid> geoid = Geoid::load(data / "egm96-geoid/egm96_15.gtx");
  ASSERT_TRUE(geoid);
  HeightGrid sea = geographicGrid(3, 3, 0.01, -0.01, 0.01);  // around (0, 0): N = 17.16 m
  Result<globe::GlobeMesh> mesh = globe::buildGlobeMesh(sea, &geoid.value(), 4);
  ASSERT_TRUE(mesh);
  const wgs84::Geodetic centre =
      wgs84::ecefToGeodetic(globe::vertexEcef(mesh->chunks[0].vertices[4]));
  EXPECT_NEAR(centre.heightM, geoid->undulationM(0.0, 0.0), 1e-6);
  EXPECT_NEAR(centre.heightM, 17.16, 0.01);
  EXPECT_EQ(mesh->chunks[0].vertices[4].heightM, 0.0f);  // the tint stays at sea level
}

TEST(GlobeMesh, AGlobalGridClosesTheAntimeridian) {
  // 1-degree samples from 180 W: 360 columns cover the globe; rows from 90 N to 90 S.
  HeightGrid world = geographicGrid(360, 181, 90.0, -180.0, 1.0);
  Result<globe::GlobeMesh> mesh = globe::buildGlobeMesh(world, nullptr, 64);
  ASSERT_TRUE(mesh) << mesh.error().message;
  EXPECT_TRUE(mesh->wrapsLongitude);
  EXPECT_EQ(mesh->triangleCount, 360u * 180u * 2u);  // the seam cell included
  // The last chunk's eastern column is column 0 again (180 E = 180 W).
  const globe::GlobeChunk& east = mesh->chunks[5];  // columns 320..360 of the first chunk row
  const globe::GlobeChunk& west = mesh->chunks[0];
  for (int j = 0; j < east.vertsY; ++j) {
    const glm::dvec3 a = globe::vertexEcef(east.vertices[std::size_t(j * east.vertsX + east.vertsX - 1)]);
    const glm::dvec3 b = globe::vertexEcef(west.vertices[std::size_t(j * west.vertsX)]);
    EXPECT_LT(glm::distance(a, b), 1e-6) << j;
  }
  HeightGrid utm(4, 4);
  utm.georef.hasGeoTransform = true;
  utm.georef.crsName = "WGS 84 / UTM zone 52N";
  Result<globe::GlobeMesh> refused = globe::buildGlobeMesh(utm, nullptr, 4);
  ASSERT_FALSE(refused);
  EXPECT_NE(refused.error().message.find("latitude/longitude"), std::string::npos);
  HeightGrid beyond = geographicGrid(4, 4, 95.0, 0.0, 1.0);
  EXPECT_FALSE(globe::buildGlobeMesh(beyond, nullptr, 4));
}

}  // namespace
}  // namespace tellus
