#pragma once
// Piecewise-linear colour ramp over height (metres). The GLSL twin is
// shaders/common/shading.glsl:rampColour(); both take the same stops.
#include <vector>

#include <glm/vec3.hpp>

namespace tellus {

struct ColourStop {
  float heightM = 0.0f;
  glm::vec3 colour{0.0f};  // linear RGB in [0, 1]
};

class ColourRamp {
 public:
  static constexpr int kMaxStops = 16;  // the shader's uniform array size

  // Stops must be non-empty, at most kMaxStops and sorted by strictly increasing height.
  explicit ColourRamp(std::vector<ColourStop> stops);

  // The classic hypsometric tint (water below 0 m, greens, tans, browns, rock, snow) in metres
  // above sea level.
  static ColourRamp hypsometric();

  // Colour at height h: linear interpolation between neighbouring stops, clamped at both ends.
  glm::vec3 evaluate(float heightM) const;

  const std::vector<ColourStop>& stops() const { return stops_; }

 private:
  std::vector<ColourStop> stops_;
};

}  // namespace tellus
