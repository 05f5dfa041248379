#pragma once
// Deterministic procedural terrain that looks like real mountains: domain-warped, eroded
// (derivative-damped) ridged multifractal noise over a large-scale relief mask, then thermal
// erosion and droplet-based hydraulic erosion. Feature sizes are in metres, so a larger grid is
// a larger area at the same spacing. The same parameters give the same heights on every run.
#include <cstdint>

#include "tellus/core/result.hpp"
#include "tellus/dem/height_grid.hpp"

namespace tellus {

struct TerrainParams {
  int size = 1025;  // the grid is size x size samples (>= 2)
  std::uint64_t seed = 1;
  double spacingM = 30.0;   // ground distance between samples, metres
  double reliefM = 2600.0;  // rough height of the highest ridges above the plains, metres
  double erosion = 1.0;     // 0 disables erosion; 1 is the default strength
};

// The ranges generateTerrain() works within (what `tellus generate` accepts).
inline constexpr int kMinTerrainSize = 2, kMaxTerrainSize = 65537;
inline constexpr double kMinTerrainSpacingM = 0.01, kMaxTerrainSpacingM = 100000.0;
inline constexpr double kMinReliefM = 1.0, kMaxReliefM = 20000.0;
inline constexpr double kMaxErosion = 10.0;
// Memory generateTerrain() takes per sample: the grid and the erosion's second buffer.
inline constexpr double kTerrainBytesPerSample = 8.0;

// Every parameter finite and within the ranges above; the error names the parameter.
Status checkTerrainParams(const TerrainParams& params);

// Runs on all cores (oneTBB). Reports progress on a terminal. Heights in metres; no georef.
// `params` must pass checkTerrainParams().
HeightGrid generateTerrain(const TerrainParams& params);

}  // namespace tellus
