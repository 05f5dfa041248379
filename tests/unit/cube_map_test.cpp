// Cube maps of the globe (seed 001): a latitude/longitude image converted to a cube map and
// sampled back in any direction gives the image there (the round trip), faces meet without a
// seam, every texel's direction lands on its own texel; the bump map of a flat altitude is the
// plain normal and a slope tilts it away from the rise.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include <glm/geometric.hpp>

#include "tellus/dem/cube_map.hpp"
#include "tellus/dem/globe_texture_set.hpp"

namespace tellus {
namespace {

constexpr double kPi = 3.14159265358979323846;

// A two-channel pattern smooth on the sphere (of the unit vector at latitude and longitude,
// degrees), 0..255.
double pattern(double latDeg, double lonDeg, int channel) {
  const double lat = latDeg * kPi / 180.0, lon = lonDeg * kPi / 180.0;
  const double x = std::cos(lat) * std::cos(lon), y = std::cos(lat) * std::sin(lon);
  const double z = std::sin(lat);
  return channel == 0 ? 128.0 + 70.0 * z + 50.0 * x * y : 128.0 + 80.0 * x - 40.0 * y * z;
}

LatLonImage patternImage(int width) {
  LatLonImage image;
  image.width = width;
  image.height = width / 2;
  image.channels = 2;
  image.pixels.resize(std::size_t(image.width) * image.height * 2);
  for (int j = 0; j < image.height; ++j) {
    for (int i = 0; i < image.width; ++i) {
      const double lat = 90.0 - (j + 0.5) * 180.0 / image.height;
      const double lon = -180.0 + (i + 0.5) * 360.0 / image.width;
      for (int c = 0; c < 2; ++c) {
        image.pixels[(std::size_t(j) * image.width + i) * 2 + std::size_t(c)] =
            std::uint8_t(std::lround(pattern(lat, lon, c)));
      }
    }
  }
  return image;
}

TEST(CubeMap, RoundTripGivesTheImageInEveryDirection) {
  const LatLonImage image = patternImage(1024);
  const CubeMap cube = latLonToCubeMap(image, 192);
  ASSERT_EQ(cube.channels, 2);
  std::mt19937 random(7);
  std::normal_distribution<double> gauss;
  double worst = 0.0;
  for (int k = 0; k < 5000; ++k) {
    const glm::dvec3 d = glm::normalize(glm::dvec3(gauss(random), gauss(random), gauss(random)));
    const double lat = std::asin(d.z) * 180.0 / kPi, lon = std::atan2(d.y, d.x) * 180.0 / kPi;
    for (int c = 0; c < 2; ++c) {
      worst = std::max(worst, std::abs(sampleCubeMap(cube, d, c) - pattern(lat, lon, c)));
    }
  }
  // 8-bit rounding twice and interpolation of a smooth pattern: about a level.
  EXPECT_LT(worst, 2.0);
  // Each texel's direction lies on that texel (the layout and its inverse agree).
  for (int face = 0; face < 6; ++face) {
    for (const auto& [column, row] : {std::pair{0, 0}, std::pair{191, 5}, std::pair{77, 191}}) {
      const glm::dvec3 d = cubeTexelDirection(face, cube.size, column, row);
      const std::uint8_t stored =
          cube.faces[std::size_t(face)][(std::size_t(row) * cube.size + column) * 2];
      EXPECT_NEAR(sampleCubeMap(cube, d, 0), stored, 1e-9) << face;
    }
  }
  // The poles, where the plate carree squeezes a row into a point, are one value.
  EXPECT_NEAR(sampleCubeMap(cube, {0.0, 0.0, 1.0}, 0), pattern(90.0, 0.0, 0), 2.0);
  EXPECT_NEAR(sampleCubeMap(cube, {0.0, 0.0, -1.0}, 0), pattern(-90.0, 0.0, 0), 2.0);
}

TEST(CubeMap, FacesMeetWithoutASeam) {
  const CubeMap cube = latLonToCubeMap(patternImage(512), 64);
  // Directions a hair either side of each cube edge sample nearly the same value.
  std::mt19937 random(3);
  std::uniform_real_distribution<double> along(-0.95, 0.95);
  for (int k = 0; k < 500; ++k) {
    const double t = along(random);
    for (const glm::dvec3& edge : {glm::dvec3(1.0, 1.0, t), glm::dvec3(1.0, t, 1.0),
                                   glm::dvec3(t, -1.0, -1.0), glm::dvec3(-1.0, t, 1.0)}) {
      const glm::dvec3 a = glm::normalize(edge + glm::dvec3(1e-4, 0.0, 0.0));
      const glm::dvec3 b = glm::normalize(edge - glm::dvec3(1e-4, 0.0, 0.0));
      EXPECT_NEAR(sampleCubeMap(cube, a, 0), sampleCubeMap(cube, b, 0), 3.0);
    }
  }
}

TEST(CubeMap, BumpMapOfFlatGroundIsTheNormalAndSlopesTiltIt) {
  LatLonImage altitude;
  altitude.width = 64;
  altitude.height = 32;
  altitude.channels = 1;
  altitude.pixels.assign(64 * 32, 40);
  const LatLonImage flat = bumpMapFromAltitude(altitude, 10.0);
  ASSERT_EQ(flat.channels, 4);
  EXPECT_EQ(flat.pixels[(10 * 64 + 20) * 4 + 0], 255);  // all normal
  EXPECT_EQ(flat.pixels[(10 * 64 + 20) * 4 + 1], 128);  // no tangent
  EXPECT_EQ(flat.pixels[(10 * 64 + 20) * 4 + 2], 128);  // no binormal
  EXPECT_EQ(flat.pixels[(10 * 64 + 20) * 4 + 3], 40);   // the altitude kept
  // Rising eastwards: the normal leans west (a negative tangent weight).
  for (int j = 0; j < 32; ++j) {
    for (int i = 0; i < 64; ++i) altitude.pixels[std::size_t(j) * 64 + i] = std::uint8_t(4 * (i % 32));
  }
  const LatLonImage slope = bumpMapFromAltitude(altitude, 2000.0);  // 625 km pixels: steep
  EXPECT_LT(slope.pixels[(16 * 64 + 10) * 4 + 1], 120);
  EXPECT_LT(slope.pixels[(16 * 64 + 10) * 4 + 0], 255);
  EXPECT_NEAR(slope.pixels[(16 * 64 + 10) * 4 + 2], 128, 1);
}

}  // namespace
}  // namespace tellus
