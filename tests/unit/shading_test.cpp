#include <gtest/gtest.h>

#include <glm/glm.hpp>

#include "tellus/render/shading/terrain_shading.hpp"

namespace tellus {
namespace {

TEST(TerrainShading, SunDirectionFollowsAzimuthAndElevation) {
  ShadingParams params;
  params.sunAzimuthDeg = 90.0;  // from the east
  params.sunElevationDeg = 0.0;
  const glm::vec3 east = params.sunDirection();
  EXPECT_NEAR(east.x, 1.0f, 1e-6f);
  EXPECT_NEAR(east.z, 0.0f, 1e-6f);
  params.sunElevationDeg = 90.0;
  EXPECT_NEAR(params.sunDirection().z, 1.0f, 1e-6f);
}

TEST(TerrainShading, FlatGroundUnderAHighSunMatchesTheFormula) {
  ShadingParams params;
  params.sunElevationDeg = 90.0;
  params.hazeDensity = 0.0f;
  const float height = 100.0f;
  const glm::vec3 albedo = params.ramp.evaluate(height);
  const glm::vec3 lit = albedo * (params.sunColour + params.skyColour);  // sun 1, sky 1
  const glm::vec3 colour = shadeTerrain(params, height, {0, 0, 1}, {0, 0, 0});
  for (int c = 0; c < 3; ++c) {
    const float l = std::clamp(lit[c], 0.0f, 1.0f);
    const float srgb = l < 0.0031308f ? l * 12.92f : 1.055f * std::pow(l, 1.0f / 2.4f) - 0.055f;
    EXPECT_NEAR(colour[c], srgb, 1e-5f);
  }
}

TEST(TerrainShading, SlopesFacingAwayFromTheSunAreDarker) {
  ShadingParams params;
  const glm::vec3 toSun = params.sunDirection();
  const glm::vec3 facing = glm::normalize(glm::vec3(toSun.x, toSun.y, 1.0f));
  const glm::vec3 away = glm::normalize(glm::vec3(-toSun.x, -toSun.y, 1.0f));
  const glm::vec3 lit = shadeTerrain(params, 300.0f, facing, {0, 0, 0});
  const glm::vec3 dark = shadeTerrain(params, 300.0f, away, {0, 0, 0});
  EXPECT_GT(lit.r + lit.g + lit.b, dark.r + dark.g + dark.b + 0.3f);
}

TEST(TerrainShading, HazeStartsAtTheTerrainAndGrowsWithDistance) {
  ShadingParams params;
  const Aabb bounds{{0, 0, 0}, {10000, 10000, 1000}};
  params.fitHazeToView(bounds, {5000, -5000, 2000}, 20000.0);
  EXPECT_NEAR(params.hazeStartM, std::sqrt(5000.0 * 5000.0 + 1000.0 * 1000.0),
              0.01);  // to the box top
  const glm::vec3 normal(0, 0, 1);
  const glm::vec3 near = shadeTerrain(params, 200.0f, normal, {0, 4000, 0});
  ShadingParams clear = params;
  clear.hazeDensity = 0.0f;
  EXPECT_EQ(near, shadeTerrain(clear, 200.0f, normal, {0, 4000, 0}));  // before the haze starts
  const glm::vec3 far = shadeTerrain(params, 200.0f, normal, {0, 20000, 0});
  const glm::vec3 sky = glm::vec3(skyColour8(params)) / 255.0f;
  EXPECT_LT(glm::length(far - sky), glm::length(near - sky));
}

}  // namespace
}  // namespace tellus
