#pragma once
// The level-of-detail hierarchy of material stacks (seed 003, section 3.1): level k + 1 has a
// stack for every 2 x 2 of level k, built by the seed's heuristic, since materials have no
// average. GL-free.
//
// The (up to) four stacks are cut into segments at every layer boundary any of them has; in a
// segment each stack holds one material (air included). Per segment:
//   1. a material held by more of the four than any other is dominant: it is chosen;
//   2. otherwise (a tie), the segments round it decide, nearest first (below and above; above
//      the highest segment is the sky, air):
//      a. if only one side's dominant material is among the tied ones, or both sides agree, it
//         is chosen;
//      b. if one tied material dominates below and another above, the segment is split in half,
//         the lower half to the one below, the upper half to the one above (a 2 : 2 tie between
//         rock and air at a ragged surface becomes the surface at its mean height);
//      c. otherwise the neighbourhood widens a segment at a time; when the column is exhausted
//         the tied material with the most thickness in the four stacks wins (solid before air
//         on equal thickness, then the lower id). Deterministic.
// Adjacent segments of one material merge into one layer; air segments are gaps.
#include <span>
#include <vector>

#include "tellus/core/result.hpp"
#include "tellus/formats/stacks/material_stack.hpp"

namespace tellus {

// The aggregate of one to four columns.
std::vector<StackLayer> aggregateColumns(std::span<const std::span<const StackLayer>> columns);

// The next level: ceil(width / 2) x ceil(height / 2) stacks, twice the spacing. Errors: an
// aggregate that is no valid terrain (a guard: valid columns aggregate to valid ones).
Result<StackTerrain> tryAggregateStackTerrain(const StackTerrain& fine);
// The same for terrains Tellus made itself (generated, built, edited): the aggregate is valid.
StackTerrain aggregateStackTerrain(const StackTerrain& fine);

// Every level from `finest` (level 0) to a single stack.
std::vector<StackTerrain> buildStackPyramid(StackTerrain finest);

}  // namespace tellus
