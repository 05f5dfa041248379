#pragma once
// Material stacks from a heightfield, with the 3D features a heightfield cannot hold (seed 003's
// test terrain, in the spirit of Geiss's GPU Gems 3 chapter it cites): the DEM's ground becomes
// rock, soil and grass; caves are carved by 3D noise (two ridged noises crossing make tubes,
// which open at the surface where they meet it: cave mouths); overhangs are lips of rock pushed
// out over the foot of cliffs; arches are rock spans between two high points across a valley.
// Rock left floating by any of them is removed: every layer is joined to the ground. GL-free,
// deterministic for a seed.
#include <cstdint>

#include "tellus/core/result.hpp"
#include "tellus/dem/height_grid.hpp"
#include "tellus/formats/stacks/material_stack.hpp"

namespace tellus {

inline constexpr StackMaterial kStackRock = 1, kStackSoil = 2, kStackGrass = 3;

struct StackFeatures {
  bool caves = true, overhangs = true, arches = true;
};

struct StackGeneratorOptions {
  StackFeatures features;
  std::uint64_t seed = 7;
  double soilDepthM = 1.5;   // on flat ground, thinning to none on slopes of 45 degrees
  double grassDepthM = 0.25;
  double caveDepthM = 40.0;  // caves lie within this depth below the surface
  double caveScaleM = 96.0;  // the caves' noise wavelength
};

// Where the generator put its features, for cameras and reports.
struct StackArch {
  int x0 = 0, y0 = 0, x1 = 0, y1 = 0;  // the span's ends, stacks (column, row; row 0 north)
  float deckTop0M = 0, deckTop1M = 0;   // the deck's top at each end, metres above the base
  float openingM = 0;                   // the tallest gap under the deck
};
struct StackFeatureReport {
  std::vector<StackArch> arches;
  std::size_t floatingLayersRemoved = 0;
};

// Heights become metres above the terrain's base, 8 m below the lowest sample (and caveDepthM
// more with caves). The grid's
// spacing becomes the stacks' (its x spacing; y must match within 1 %). Errors: an empty grid,
// anisotropic spacing, caves that would take more than kMaxCaveSamples noise samples (a
// spacing far finer than the grid's extent needs: the message gives the finest that works).
// `report`, when given, receives where the arches are.
// The cave pass's budget: samples of its 3D noise (about a minute on two cores).
inline constexpr double kMaxCaveSamples = 2e9;

Result<StackTerrain> generateStacks(const HeightGrid& grid, const StackGeneratorOptions& options,
                                    StackFeatureReport* report = nullptr);

// The grid resampled (bilinearly) onto square cells of its smaller spacing, when its x and y
// spacings differ by more than 1 % (latitude/longitude DEMs such as SRTM: 74 x 93 m at 36 N);
// otherwise a copy.
HeightGrid squareCells(const HeightGrid& grid);

// Removes every layer not joined to the ground (the layers starting at 0) through layers that
// touch in a column or overlap across a side of it. Returns how many it removed.
std::size_t removeFloatingLayers(int width, int height, std::vector<std::vector<StackLayer>>& columns);

}  // namespace tellus
