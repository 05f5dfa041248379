#pragma once
// The stack terrain the stack tests share: rolling hills rising eastwards, with the
// generator's caves, overhangs and arches carved into them (seed 003's kind of terrain).
#include "tellus/core/result.hpp"
#include "tellus/formats/stacks/material_stack.hpp"

namespace tellus::test {

// Heights amplitudeM * sin(x * waveX) * cos(y * waveY) + riseM * x (x, y in samples), spacingM
// apart; caves of caveScaleM (0: the generator's default).
struct HillsWithCaves {
  int width = 96, height = 80;
  double amplitudeM = 30.0;
  double waveX = 0.13, waveY = 0.11;
  double riseM = 0.6;  // per sample eastwards
  double caveScaleM = 32.0;
  double spacingM = 4.0;
};

Result<StackTerrain> hillsWithCaves(const HillsWithCaves& shape);

}  // namespace tellus::test
