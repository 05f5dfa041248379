#include "tellus/lod/spiral/spiral_radius.hpp"

#include <algorithm>
#include <cmath>

namespace tellus {

SpiralRadii spiralAnalyticRadii(double clearanceM, double eyeHeightM, double radiusM,
                                double focalLengthPx, double fanPixels) {
  SpiralRadii radii;
  // A disc of radius rho metres at distance c covers pi (rho f / c)^2 pixels.
  const double fanM = std::sqrt(fanPixels / M_PI) * std::max(clearanceM, 1.0) / focalLengthPx;
  radii.minRad = fanM / radiusM;
  const double eye = std::max(eyeHeightM, 0.0);
  radii.maxRad = std::acos(radiusM / (radiusM + eye)) +
                 std::acos(radiusM / (radiusM + kSpiralHighestGroundM));
  return radii;
}

void SpiralRadiusFeedback::update(std::uint64_t fanPixels, std::uint64_t outerPixels,
                                  double lowestRad, double highestRad) {
  const SpiralFeedbackParams& p = params_;
  // The fan: pixels grow as the radius squared, so hitting the target at once would scale the
  // radius by sqrt(target / pixels); take the damped share of that step, bounded.
  const double target = p.fanPixels;
  double logStep = 0.0;
  const double maxLog = std::log(p.maxStepFactor);
  if (fanPixels == 0) {
    // The fan is off screen (the camera looks ahead) or hidden: its size cannot be judged, and
    // growing it until it shows would flatten the ground under the view. Hold.
    logStep = 0.0;
  } else if (double(fanPixels) > target * (1.0 + p.fanBand) ||
             double(fanPixels) < target / (1.0 + p.fanBand)) {
    logStep = std::clamp(p.damping * 0.5 * std::log(target / double(fanPixels)), -maxLog, maxLog);
  }
  radii_.minRad *= std::exp(logStep);
  // The last revolution: visible and more than a trace, there may be more to show; wholly
  // hidden, it is not needed.
  if (double(outerPixels) > p.outerFastPixels) {
    radii_.maxRad *= p.outerStepFactor * p.outerStepFactor;
  } else if (double(outerPixels) > p.outerGrowPixels) {
    radii_.maxRad *= p.outerStepFactor;
  } else if (outerPixels == 0) {
    radii_.maxRad /= p.outerStepFactor;
  }
  radii_.maxRad = std::clamp(radii_.maxRad, lowestRad, highestRad);
  radii_.minRad = std::clamp(radii_.minRad, lowestRad, radii_.maxRad * 0.5);
}

}  // namespace tellus
