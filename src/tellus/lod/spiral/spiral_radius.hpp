#pragma once
// Which part of the spiral to draw (seed 001, "Other Uses for occlusion_query for LOD"): the
// minimum radius (the central fan's edge) and the maximum (the last revolution). GL-free.
//
// Two ways, both reported by the renderer:
//   - the seed's feedback: the fan's pixel count (an occlusion query) against a target moves the
//     minimum radius, and the last revolution's pixel count moves the maximum; the counts arrive
//     a frame late (never stalling the GPU) and the steps are damped (below);
//   - an analytic choice from the camera: the fan's radius for its target seen straight down,
//     and the horizon (the eye's, plus that of the highest mountains beyond it).
// Radii are radians of arc round the focal point (spiral_projection.hpp).
#include <cstdint>

namespace tellus {

struct SpiralRadii {
  double minRad = 1e-4;
  double maxRad = 1.0;
};

// The highest ground on Earth, metres: terrain beyond the eye's horizon up to this height can
// still show above it.
inline constexpr double kSpiralHighestGroundM = 9000.0;

// The analytic choice: the fan covering `fanPixels` pixels when seen from `clearanceM` above the
// ground straight down with a focal length of `focalLengthPx` pixels, and the horizon of an eye
// `eyeHeightM` above a sphere of `radiusM`, plus the highest ground's.
SpiralRadii spiralAnalyticRadii(double clearanceM, double eyeHeightM, double radiusM,
                                double focalLengthPx, double fanPixels);

struct SpiralFeedbackParams {
  double fanPixels = 256.0;  // the fan's target, pixels
  // A count of 0 (the fan off screen or hidden) holds the minimum radius.
  // The fan's dead band: no change while the count is within [target / (1 + band),
  // target * (1 + band)] (hysteresis: no hunting around the target).
  double fanBand = 0.3;
  // The damping: the minimum radius moves by this fraction of the step that would hit the
  // target at once (pixels grow as the radius squared) ...
  // The counts arrive a frame or two late: with that delay a gain below about 0.5 settles
  // without overshoot.
  double damping = 0.4;
  // ... and by at most this factor a frame (the seed's "small value", so that a jump can never
  // overshoot far enough to explode; a descent to the ground halves the clearance every few
  // frames).
  double maxStepFactor = 2.0;
  // The last revolution: a count above this grows the maximum radius, a count of 0 (all of it
  // hidden behind the horizon or off screen) shrinks it.
  double outerGrowPixels = 4.0;
  // The maximum radius's step a frame, as a factor (the renderer sets about a quarter
  // revolution); counts above outerFastPixels grow it by the square of that.
  double outerStepFactor = 1.2;
  double outerFastPixels = 2000.0;
};

class SpiralRadiusFeedback {
 public:
  SpiralRadiusFeedback(SpiralRadii initial, SpiralFeedbackParams params)
      : radii_(initial), params_(params) {}

  // One frame's counts (read a frame or more after they were drawn): moves the radii for the
  // next frame, clamped to [lowestRad, highestRad] (the mesh's extent), min below max.
  void update(std::uint64_t fanPixels, std::uint64_t outerPixels, double lowestRad,
              double highestRad);
  const SpiralRadii& radii() const { return radii_; }
  void reset(SpiralRadii radii) { radii_ = radii; }

 private:
  SpiralRadii radii_;
  SpiralFeedbackParams params_;
};

}  // namespace tellus
