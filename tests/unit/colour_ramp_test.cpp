#include <gtest/gtest.h>

#include "tellus/core/colour_ramp.hpp"

namespace tellus {
namespace {

TEST(ColourRamp, InterpolatesBetweenStopsAndClampsAtTheEnds) {
  const ColourRamp ramp({{0.0f, {0, 0, 0}}, {100.0f, {1, 0.5f, 0}}, {300.0f, {1, 1, 1}}});
  EXPECT_EQ(ramp.evaluate(-1000.0f), glm::vec3(0, 0, 0));
  EXPECT_EQ(ramp.evaluate(0.0f), glm::vec3(0, 0, 0));
  EXPECT_EQ(ramp.evaluate(100.0f), glm::vec3(1, 0.5f, 0));
  const glm::vec3 mid = ramp.evaluate(50.0f);
  EXPECT_FLOAT_EQ(mid.r, 0.5f);
  EXPECT_FLOAT_EQ(mid.g, 0.25f);
  EXPECT_FLOAT_EQ(ramp.evaluate(200.0f).g, 0.75f);
  EXPECT_EQ(ramp.evaluate(1e6f), glm::vec3(1, 1, 1));
}

TEST(ColourRamp, HypsometricTintReadsAsWaterLandAndSnow) {
  const ColourRamp ramp = ColourRamp::hypsometric();
  const glm::vec3 sea = ramp.evaluate(0.0f), deep = ramp.evaluate(-150.0f);
  EXPECT_GT(sea.b, sea.g);
  EXPECT_GT(sea.b, sea.r);
  EXPECT_GT(deep.b, deep.r);
  const glm::vec3 lowland = ramp.evaluate(100.0f);
  EXPECT_GT(lowland.g, lowland.r);
  EXPECT_GT(lowland.g, lowland.b);
  const glm::vec3 snow = ramp.evaluate(5000.0f);
  EXPECT_GT(snow.r, 0.9f);
  EXPECT_GT(snow.b, 0.9f);
  EXPECT_LE(ramp.stops().size(), size_t(ColourRamp::kMaxStops));
}

}  // namespace
}  // namespace tellus
