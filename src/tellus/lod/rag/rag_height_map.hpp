#pragma once
// The height map RAG refines against, for terrains larger than one GPU texture (seed 004 kept one
// height map in GPU memory). When the grid has more samples a side than the texture may hold,
// RAG uses a coarser pyramid level of it instead: every 2^level-th sample, counted from the
// south-western sample (the world origin, so world coordinates do not change), exactly the
// samples a tile store keeps at that level. Columns east of and rows north of the last whole
// step are left out (fewer than 2^level of each; none for 2^n + 1 grids).
//
// What it costs: the level cannot show detail finer than its spacing, so every refined vertex
// may be off the full-resolution surface by up to the level's geometric error, max |h - I_L|
// over all covered samples with I_L the level interpolated bilinearly (the store's definition).
#include "tellus/dem/height_grid.hpp"

namespace tellus::rag {

// The smallest level whose grid has at most maxSide samples on each side (0 when the grid fits).
int heightMapLevel(int width, int height, int maxSide);

struct HeightMap {
  HeightGrid grid;     // the samples RAG uploads; spacing 2^level times the input's
  int level = 0;
  float errorM = 0.0f;  // max |h - I_L| over the covered samples, metres (0 at level 0)
  int droppedColumns = 0, droppedRows = 0;  // east and north strips left out
};

// The input's level `level` (level 0: a copy). Computes the error on all cores.
HeightMap heightMapAtLevel(const HeightGrid& full, int level);

}  // namespace tellus::rag
