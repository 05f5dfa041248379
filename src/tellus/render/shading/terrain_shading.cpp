#include "tellus/render/shading/terrain_shading.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

#include <glm/common.hpp>
#include <glm/exponential.hpp>
#include <glm/geometric.hpp>
#include <glm/gtc/constants.hpp>
#include <glm/vec3.hpp>

#include "tellus/gl/program.hpp"

namespace tellus {
namespace {

glm::vec3 linearToSrgb(glm::vec3 c) {
  c = glm::clamp(c, 0.0f, 1.0f);
  glm::vec3 out;
  for (int i = 0; i < 3; ++i) {
    out[i] = c[i] < 0.0031308f ? c[i] * 12.92f : 1.055f * std::pow(c[i], 1.0f / 2.4f) - 0.055f;
  }
  return out;
}

}  // namespace

glm::vec3 ShadingParams::sunDirection() const {
  const double az = sunAzimuthDeg * glm::pi<double>() / 180.0;
  const double el = sunElevationDeg * glm::pi<double>() / 180.0;
  return glm::normalize(glm::vec3(float(std::sin(az) * std::cos(el)),
                                  float(std::cos(az) * std::cos(el)), float(std::sin(el))));
}

void ShadingParams::fitHazeToView(const Aabb& bounds, const glm::dvec3& cameraPosition,
                                  double farM) {
  const double start = bounds.distanceTo(cameraPosition);
  hazeStartM = float(start);
  hazeDensity = float(-std::log(1.0 - 0.3) / std::max(1.0, farM - start));
}

glm::vec3 shadeTerrain(const ShadingParams& params, float heightM, const glm::vec3& normal,
                       const glm::vec3& relativePosition) {
  glm::vec3 albedo = params.ramp.evaluate(heightM);
  const float steepness = 1.0f - normal.z;
  const float rock =
      params.slopeRock * glm::smoothstep(0.25f, 0.55f, steepness) * (heightM >= 0.5f ? 1.0f : 0.0f);
  albedo = glm::mix(albedo, glm::vec3(0.26f, 0.23f, 0.20f), rock);
  const float sun = std::max(glm::dot(normal, params.sunDirection()), 0.0f);
  const float skyVisibility = 0.5f + 0.5f * normal.z;
  const glm::vec3 lit = albedo * (params.sunColour * sun + params.skyColour * skyVisibility);
  const float haze =
      1.0f - std::exp(-std::max(glm::length(relativePosition) - params.hazeStartM, 0.0f) *
                      params.hazeDensity);
  return linearToSrgb(glm::mix(lit, params.hazeColour, haze));
}

glm::u8vec3 skyColour8(const ShadingParams& params) {
  const glm::vec3 srgb = linearToSrgb(params.hazeColour);
  return glm::u8vec3(glm::round(srgb * 255.0f));
}

void applyShading(const gl::Program& program, const ShadingParams& params) {
  const auto& stops = params.ramp.stops();
  std::vector<float> heights;
  std::vector<glm::vec3> colours;
  for (const ColourStop& stop : stops) {
    heights.push_back(stop.heightM);
    colours.push_back(stop.colour);
  }
  program.set("uRampStopCount", int(stops.size()));
  program.setArray("uRampHeights", heights.data(), int(heights.size()));
  program.setArray("uRampColours", colours.data(), int(colours.size()));
  program.set("uSunDirection", params.sunDirection());
  program.set("uSunColour", params.sunColour);
  program.set("uSkyColour", params.skyColour);
  program.set("uHazeColour", params.hazeColour);
  program.set("uHazeDensity", params.hazeDensity);
  program.set("uHazeStart", params.hazeStartM);
  program.set("uSlopeRock", params.slopeRock);
}

}  // namespace tellus
