// The procedural planet: deterministic, seamless across the antimeridian and at the poles (the
// noise lives on the sphere), oceans and continents in sensible shares, georeferenced as the
// whole globe, and a plateau where one is asked for.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "tellus/dem/planet_generator.hpp"

namespace tellus {
namespace {

TEST(PlanetGenerator, IsDeterministicAndCoversTheGlobe) {
  const HeightGrid a = generatePlanet({.columns = 360, .seed = 3, .plateau = std::nullopt});
  const HeightGrid b = generatePlanet({.columns = 360, .seed = 3, .plateau = std::nullopt});
  const HeightGrid c = generatePlanet({.columns = 360, .seed = 4, .plateau = std::nullopt});
  ASSERT_EQ(a.width, 360);
  ASSERT_EQ(a.height, 180);
  EXPECT_EQ(a.heights, b.heights);
  EXPECT_NE(a.heights, c.heights);
  const auto& gt = a.georef.geoTransform;
  EXPECT_DOUBLE_EQ(gt[0], -180.0);
  EXPECT_DOUBLE_EQ(gt[3], 90.0);
  EXPECT_DOUBLE_EQ(gt[0] + a.width * gt[1], 180.0);
  EXPECT_DOUBLE_EQ(gt[3] + a.height * gt[5], -90.0);
  EXPECT_TRUE(a.georef.isGeographic);
  EXPECT_FALSE(a.georef.crsWkt.empty());
}

TEST(PlanetGenerator, HasNoSeamAtTheAntimeridianOrThePoles) {
  const HeightGrid g = generatePlanet({.columns = 720, .seed = 1, .plateau = std::nullopt});
  // The typical step between east-west neighbours, and the step across 180 degrees.
  double typical = 0.0, across = 0.0;
  for (int j = 0; j < g.height; ++j) {
    for (int i = 0; i + 1 < g.width; ++i) typical += std::abs(g.at(i + 1, j) - g.at(i, j));
    across += std::abs(g.at(0, j) - g.at(g.width - 1, j));
  }
  typical /= double(g.height) * (g.width - 1);
  across /= g.height;
  EXPECT_LT(across, 2.0 * typical);
  // Round the pole the row varies no more than a step apart (points 0.25 degrees apart).
  const auto [lo, hi] = std::minmax_element(g.heights.begin(), g.heights.begin() + g.width);
  EXPECT_LT(*hi - *lo, 20.0 * typical);
}

TEST(PlanetGenerator, HasOceansAndContinents) {
  const HeightGrid g = generatePlanet({.columns = 720, .seed = 7, .highestM = 6000.0,
                                       .plateau = std::nullopt});
  double land = 0.0, total = 0.0;
  for (int j = 0; j < g.height; ++j) {
    const double lat = 90.0 - (j + 0.5) * 0.5;
    const double area = std::cos(lat * 3.14159265358979323846 / 180.0);
    for (int i = 0; i < g.width; ++i) {
      total += area;
      if (g.at(i, j) > 0.0f) land += area;
    }
  }
  EXPECT_GT(land / total, 0.15);
  EXPECT_LT(land / total, 0.6);
  const HeightRange range = g.heightRange();
  EXPECT_GT(range.maxM, 2000.0f);
  EXPECT_LT(range.maxM, 9000.0f);
  EXPECT_LT(range.minM, -2000.0f);
}

TEST(PlanetGenerator, APlateauHoldsItsHeightAndBlendsOut) {
  const PlanetPlateau plateau{.latDeg = 46.9, .lonDeg = 13.7, .radiusDeg = 2.0, .heightM = 777.0};
  const HeightGrid flat = generatePlanet({.columns = 720, .seed = 2, .plateau = std::nullopt});
  const HeightGrid g = generatePlanet({.columns = 720, .seed = 2, .plateau = plateau});
  const auto sampleAt = [](const HeightGrid& grid, double lat, double lon) {
    const int i = int((lon + 180.0) / 0.5), j = int((90.0 - lat) / 0.5);
    return grid.at(i, j);
  };
  EXPECT_FLOAT_EQ(sampleAt(g, 46.9, 13.7), 777.0f);
  EXPECT_FLOAT_EQ(sampleAt(g, 47.9, 14.2), 777.0f);             // within the radius
  EXPECT_EQ(sampleAt(g, 40.0, 13.7), sampleAt(flat, 40.0, 13.7));  // beyond twice the radius
  EXPECT_EQ(sampleAt(g, -30.0, -100.0), sampleAt(flat, -30.0, -100.0));
}

}  // namespace
}  // namespace tellus
