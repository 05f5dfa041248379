#pragma once
// Camera paths inside stack terrain (seed 003's caves and arches), for `bench --path cave`:
// the largest connected passage under solid ground (a cave, or the opening under an arch),
// walked end to end at 40 % of its height, looking along it. GL-free.
//
// A column is in a passage when it has an air gap between two solid layers at least
// minGapM tall; neighbouring columns (4-connected) join when their gaps overlap by half that.
// The walk follows the passage's longest shortest path (two breadth-first searches), with a
// keyframe every few columns.
#include "tellus/core/result.hpp"
#include "tellus/eval/camera_path.hpp"
#include "tellus/formats/stacks/material_stack.hpp"

namespace tellus {

struct StackPassage {
  std::size_t columns = 0;       // in the passage
  double lengthM = 0.0;          // of the walk
  double meanGapM = 0.0;         // mean opening height along the walk
};

// Errors: no passage of at least minGapM (and 8 columns).
Result<CameraPath> makeCavePath(const StackTerrain& stacks, double minGapM = 6.0,
                                StackPassage* passage = nullptr);

}  // namespace tellus
