#pragma once
// Shared fixtures of the GPU tests of the globe renderers that stream from a global store
// (RINGO, the spiral): a synthetic Earth store and a count of holes in a rendered frame.
#include <memory>

#include "support/terrain_fixtures.hpp"
#include "tellus/core/camera.hpp"
#include "tellus/tiles/global_store.hpp"

namespace tellus::test {

// The relief of syntheticEarth(): kilometres of smooth relief with 400 m ripples.
double syntheticEarthRelief(double latDeg, double lonDeg);

// A global store of 32-cell tiles of `relief`, built in a fresh directory: a planet of
// 0.5-degree samples (depth 4) and 0.005-degree samples over 10..14 E, 40..44 N (depth 10
// there). Fails the current test (and returns null) when it cannot.
std::shared_ptr<const GlobalStore> buildSyntheticEarth(double (*relief)(double latDeg, double lonDeg));

// buildSyntheticEarth(syntheticEarthRelief), built once per process.
std::shared_ptr<const GlobalStore> syntheticEarth();

// Pixels whose ray meets the ellipsoid within `reachM` of the eye but show the sentinel
// background: holes in the ground. Pixels within 3 px of the Earth's limb are left out: there
// coarse chords pass inside the ellipsoid's silhouette; that is level of detail, not a crack
// (the harness judges it against the reference's coverage).
int groundHoles(const RenderedFrame& frame, const ViewSetup& view, double reachM);

// Two frames of one view compared through their depth buffers, every `step`-th pixel: the
// largest distance, metres, between the points they show, over the pixels both cover.
// `holes` counts the pixels `drawn` leaves empty, `compared` those compared.
struct DepthComparison {
  double worstM = 0.0;
  int compared = 0;
  int holes = 0;
};
DepthComparison compareDepths(const RenderedFrame& drawn, const RenderedFrame& truth,
                              const ViewSetup& view, int step);

}  // namespace tellus::test
