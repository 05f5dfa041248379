#pragma once
// How a global build (global_store_builder.hpp) splits its quadtree between ranks and lays its
// tiles out in the file, as pure functions of the tile set:
//
// - The split depth S: the tiles of depth S are the roots of subtrees, each built whole by one
//   rank; the "coarse" tiles above S are made by every rank from the subtrees' roots.
// - The subtrees are dealt to ranks in contiguous runs of equal work (work measured in source
//   samples read, not tiles).
// - The file order is the quadtree's post-order (a tile's four subtrees NW, NE, SW, SE, then the
//   tile): every subtree is one contiguous run of bytes whatever S is, so the store's bytes do not
//   depend on S, on the number of ranks or on the order threads finish tiles.
#include <cstddef>
#include <vector>

#include "tellus/tiles/global_tiling.hpp"

namespace tellus {

// `key`'s ancestor at `depth` (<= key.depth); the key itself at its own depth.
GeoTileKey ancestorAt(GeoTileKey key, int depth);

// Strict weak order of the quadtree's post-order: descendants before their ancestor, and of two
// tiles in different branches, the one in the earlier branch (NW, NE, SW, SE; x = 0 before 1 at
// depth 0) first.
bool postOrderLess(GeoTileKey a, GeoTileKey b);

// A tile and the work of building it (source samples read plus its own samples).
struct TileWork {
  GeoTileKey key;
  double cost = 0.0;
};
// Roots at most: every rank holds every second sample of each (66 KiB with 256-cell tiles).
inline constexpr std::size_t kMaxSubtrees = 4096;

// The shallowest depth whose subtrees (a tile of that depth with all its descendants) each hold
// at most 1 / (8 * ranks) of the subtrees' work, so that the ranks and their threads can share it
// evenly, among the depths of at most kMaxSubtrees tiles; where none does, the one of those whose
// largest subtree holds the least. (The tiles above the split are made from their children's
// samples: their warps drop out of the work.) Fine sources over a small part of the globe need a
// deeper split than the global source's complete depths would suggest.
int chooseSplitDepth(const std::vector<TileWork>& tiles, int ranks);

// Deals items (subtrees, in file order) of the given costs to `ranks` ranks in contiguous runs:
// item i goes to the rank whose share [r, r + 1) * total / ranks holds the middle of its cost
// interval. Returns each item's rank.
std::vector<int> dealContiguous(const std::vector<double>& costs, int ranks);

}  // namespace tellus
