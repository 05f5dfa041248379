#pragma once
// RINGO (seed 002): the heights of a block, read from a global store or derived from the same
// block one or more levels finer. GL-free.
//
// A block of level L over the depth-D tile (D, x, y) holds (cells + 1)^2 samples,
// cells = tileCells / 2^L, at every 2^L-th sample point of that tile (row 0 north): the store's
// surface at depth D there (storeSampleSource: the tile's deepest stored source, and on the
// tile's edges and corners the deepest source among the tiles that meet there). That surface
// is one function of the point, so blocks side by side agree on their shared edge, and the
// tiles nest, so those points are also the depth D - L surface's samples: a block's even edge
// samples are what its coarser neighbour holds there, and a block that coarsens by k levels is
// its own samples taken every 2^k-th, bit for bit.
#include <span>
#include <vector>

#include "tellus/core/result.hpp"
#include "tellus/lod/ringo/ringo_block_matrix.hpp"
#include "tellus/tiles/global_store.hpp"

namespace tellus {

// The heights (metres as stored) of `block` (which must exist) with `layout`'s cells.
Result<std::vector<float>> loadRingoBlock(const GlobalStore& store, const RingoLayout& layout,
                                          const RingoBlock& block);

// The block `levels` levels coarser than `finer` (a block of `finerCells` cells a side):
// every 2^levels-th sample.
std::vector<float> coarsenRingoBlock(std::span<const float> finer, int finerCells, int levels);

// The height a block's mesh draws at fractional sample position (u east, v south; clamped into
// the block): its cell split from north-east to south-west into two triangles, as the grid's
// index buffer draws it. The ground the camera must stay above (seed 002's collision test).
double ringoDrawnHeight(std::span<const float> heights, int cells, double u, double v);

}  // namespace tellus
