#include "tellus/core/colour_ramp.hpp"

#include <cassert>

#include <glm/common.hpp>

namespace tellus {

ColourRamp::ColourRamp(std::vector<ColourStop> stops) : stops_(std::move(stops)) {
  assert(!stops_.empty() && stops_.size() <= kMaxStops && "ColourRamp: 1..16 stops");
  for (size_t i = 1; i < stops_.size(); ++i) {
    assert(stops_[i].heightM > stops_[i - 1].heightM && "ColourRamp: heights must increase");
  }
}

ColourRamp ColourRamp::hypsometric() {
  // Linear-space colours; the renderer converts to sRGB on output.
  return ColourRamp({
      {-200.0f, {0.010f, 0.045f, 0.120f}},  // deep water
      {0.0f, {0.035f, 0.120f, 0.260f}},     // shallow water, sea level
      {0.01f, {0.090f, 0.200f, 0.070f}},    // coastal lowland
      {150.0f, {0.120f, 0.260f, 0.080f}},   // lowland green
      {500.0f, {0.250f, 0.320f, 0.110f}},   // hills
      {1000.0f, {0.420f, 0.380f, 0.180f}},  // uplands, tan
      {1600.0f, {0.380f, 0.270f, 0.160f}},  // mountains, brown
      {2300.0f, {0.380f, 0.350f, 0.330f}},  // bare rock
      {3000.0f, {0.700f, 0.700f, 0.700f}},  // high rock
      {3600.0f, {0.950f, 0.950f, 0.970f}},  // snow
  });
}

glm::vec3 ColourRamp::evaluate(float heightM) const {
  if (heightM <= stops_.front().heightM) return stops_.front().colour;
  for (size_t i = 1; i < stops_.size(); ++i) {
    if (heightM <= stops_[i].heightM) {
      const ColourStop& a = stops_[i - 1];
      const ColourStop& b = stops_[i];
      const float t = (heightM - a.heightM) / (b.heightM - a.heightM);
      return glm::mix(a.colour, b.colour, t);
    }
  }
  return stops_.back().colour;
}

}  // namespace tellus
